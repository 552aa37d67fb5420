//! An object's geometry beyond loaded meshes: geometry shaders, parametric surfaces,
//! subdivision meshes and scatters ([`shapes`], [`scatter`]), its approximation and
//! displacement ([`dicing`]).
//!
//! Every value is checked where it is written, and the geometry code's own validation
//! (`procedural::validate`, `PatchMeshSource::new`, `NurbsSource::new`, the subdivision
//! refinement, `displace::validate`, the approximation's rate context, the scatter
//! placement rules) runs at load time, so its `GeometryError`s are reported as located
//! diagnostics instead of failing a stage. The results become the components that
//! `expand_geometry` and `tessellate` consume (see `docs/geometry.md`).

pub(crate) mod dicing;
pub(crate) mod height_map;
pub(crate) mod scatter;
pub(crate) mod shapes;

use hecs::EntityBuilder;

use super::desc::{MeshDesc, ObjectDesc};
use super::diagnostics::Sources;
use super::validate::{Checker, Item, Merged};
use crate::components::{
    Approximation, DerivativeRequest, Displacement, DisplacementMode, ObjectLabel, Procedural,
    ReverseOrientation, ScalarNode, Scatter, SubdivMesh, Surface,
};
use crate::tessellation::GeometryError;

/// What a stage generates an object's mesh from.
#[derive(Debug, Clone)]
pub enum Generated {
    /// A geometry shader (`expand_geometry`).
    Procedural(Procedural),
    /// A parametric surface (`tessellate`).
    Surface(Surface),
    /// A Catmull-Clark control mesh (`tessellate`).
    Subdiv(SubdivMesh),
    /// A scatter (`expand_geometry`); entities are filled in when spawning.
    Scatter {
        /// Prototype object (index into `Merged::objects`).
        prototype: usize,
        /// Surface object (index into `Merged::objects`).
        surface: usize,
        /// The component with dangling entities.
        template: Scatter,
    },
}

/// The checked geometry components of one object (other than a loaded mesh).
#[derive(Debug, Clone, Default)]
pub struct ObjectGeometry {
    /// The generator, for objects whose mesh a stage makes.
    pub generated: Option<Generated>,
    /// The approximation, if written.
    pub approximation: Option<Approximation>,
    /// The displacement, if written.
    pub displacement: Option<Displacement>,
    /// Whether surface derivatives are requested.
    pub derivatives: bool,
    /// Whether its front is the object-space back ([`ReverseOrientation`]).
    pub reverse_orientation: bool,
    /// Its label ([`ObjectLabel`]), if written.
    pub label: Option<u32>,
}

impl ObjectGeometry {
    /// Adds the components to an object entity (scatter entities are set by the caller).
    pub fn add_to(&self, b: &mut EntityBuilder) {
        match &self.generated {
            Some(Generated::Procedural(p)) => drop(b.add(*p)),
            Some(Generated::Surface(s)) => drop(b.add(s.clone())),
            Some(Generated::Subdiv(s)) => drop(b.add(s.clone())),
            Some(Generated::Scatter { .. }) | None => {}
        }
        if let Some(a) = self.approximation {
            b.add(a);
        }
        if let Some(d) = &self.displacement {
            b.add(d.clone());
        }
        if self.derivatives {
            b.add(DerivativeRequest);
        }
        if self.reverse_orientation {
            b.add(ReverseOrientation);
        }
        if let Some(label) = self.label {
            b.add(ObjectLabel(label));
        }
    }
}

/// Whether a stage generates this mesh (everything but mesh files and `Inline`).
pub fn is_generated(mesh: &MeshDesc) -> bool {
    !is_loaded(mesh)
}

/// Whether the loader builds this mesh: a mesh file or `Inline`.
pub fn is_loaded(mesh: &MeshDesc) -> bool {
    matches!(mesh, MeshDesc::Inline { .. }) || super::mesh_files::mesh_file(mesh).is_some()
}

/// Short name of a mesh kind for messages (`"torus"`, `"OBJ mesh"`).
pub fn kind_name(mesh: &MeshDesc) -> &'static str {
    match mesh {
        MeshDesc::Obj { .. } => "OBJ mesh",
        MeshDesc::Ply { .. } => "PLY mesh",
        MeshDesc::Gltf { .. } => "glTF mesh",
        MeshDesc::Inline { .. } => "inline mesh",
        MeshDesc::Sphere { .. } => "sphere",
        MeshDesc::Cylinder { .. } => "cylinder",
        MeshDesc::Cone { .. } => "cone",
        MeshDesc::Disk { .. } => "disk",
        MeshDesc::Torus { .. } => "torus",
        MeshDesc::Stairs { .. } => "stairs",
        MeshDesc::Grid { .. } => "grid",
        MeshDesc::PatchMesh { .. } => "patch mesh",
        MeshDesc::Nurbs { .. } => "nurbs",
        MeshDesc::Subdiv { .. } => "subdiv",
        MeshDesc::Scatter { .. } => "scatter",
    }
}

/// Whether the mesh of this object will carry texture coordinates (for `bake: (uvs: Mesh)`):
/// every generated surface does, a scatter has no surface of its own.
pub fn generated_has_uvs(mesh: &MeshDesc) -> bool {
    is_generated(mesh) && !matches!(mesh, MeshDesc::Scatter { .. })
}

/// Checks the geometry of every object (reachable or not). `scatters` are the resolved
/// scatter references ([`scatter::resolve`]). `None` where a check failed.
pub fn check_objects(
    src: &mut Sources,
    m: &Merged<'_>,
    scatters: &[Option<(usize, usize)>],
) -> Vec<Option<ObjectGeometry>> {
    m.objects
        .iter()
        .zip(scatters)
        .map(|(it, refs)| check_object(src, it, *refs))
        .collect()
}

fn check_object(
    src: &mut Sources,
    it: &Item<'_, ObjectDesc>,
    refs: Option<(usize, usize)>,
) -> Option<ObjectGeometry> {
    let d = it.desc;
    let dir = src.files[it.file].dir().to_path_buf();
    let mut ck = Checker { src, file: it.file };
    let ctx = Ctx {
        object: &d.name,
        base: it.at(".mesh"),
    };
    let mut ok = true;
    let generated = match &d.mesh {
        mesh if is_loaded(mesh) => None,
        MeshDesc::Scatter { .. } => match (scatter::template(&mut ck, &ctx, &d.mesh), refs) {
            (Some(template), Some((prototype, surface))) => Some(Generated::Scatter {
                prototype,
                surface,
                template,
            }),
            _ => {
                ok = false;
                None
            }
        },
        mesh => {
            let g = shapes::generator(&mut ck, &ctx, mesh);
            ok &= g.is_some();
            g
        }
    };
    let is_scatter = matches!(d.mesh, MeshDesc::Scatter { .. });
    let approximation = match &d.approximation {
        Some(_) if is_scatter => {
            ck.error(
                &it.at(".approximation"),
                "a scatter has no surface of its own to approximate: give the prototype an approximation",
            );
            ok = false;
            None
        }
        Some(a) => {
            let a = dicing::approximation(&mut ck, &d.name, &it.at(".approximation"), a);
            ok &= a.is_some();
            a
        }
        None => None,
    };
    let displacement = match &d.displacement {
        Some(_) if is_scatter => {
            ck.error(
                &it.at(".displacement"),
                "a scatter has no surface of its own to displace: displace the prototype",
            );
            ok = false;
            None
        }
        Some(disp) => {
            let x = dicing::displacement(&mut ck, &dir, &d.name, &it.at(".displacement"), disp);
            ok &= x.is_some();
            x
        }
        None => None,
    };
    if d.derivatives && is_scatter {
        ck.error(
            &it.at(".derivatives"),
            "a scatter has no surface of its own: request derivatives on the prototype",
        );
        ok = false;
    }
    if d.reverse_orientation && is_scatter {
        ck.error(
            &it.at(".reverse_orientation"),
            "a scatter has no surface of its own: reverse the orientation of the prototype",
        );
        ok = false;
    }
    if d.label.is_some() && is_scatter {
        ck.error(
            &it.at(".label"),
            "a scatter has no surface of its own: label the prototype",
        );
        ok = false;
    }
    let displacement = displacement.map(|x| along_front(x, d.reverse_orientation));
    ok.then_some(ObjectGeometry {
        generated,
        approximation,
        displacement,
        derivatives: d.derivatives,
        reverse_orientation: d.reverse_orientation,
        label: d.label,
    })
}

/// The displacement of an object whose orientation is `reversed`: true displacement moves
/// the object-space surface along its object-space normal in `tessellate`, so it is negated
/// to move along the reversed normal; bump displacement already follows the shading normal,
/// which is on the side of the (reversed) front.
fn along_front(d: Displacement, reversed: bool) -> Displacement {
    if !(reversed && d.mode == DisplacementMode::True) {
        return d;
    }
    Displacement {
        shader: ScalarNode::Product(vec![ScalarNode::Constant(-1.0), d.shader]),
        ..d
    }
}

/// Located warnings on settings that have no effect (an approximation of a flat mesh
/// without true displacement), at the setting.
pub fn warnings(src: &mut Sources, m: &Merged<'_>, geometry: &[Option<ObjectGeometry>]) {
    for (it, g) in m.objects.iter().zip(geometry) {
        let Some(g) = g else { continue };
        let polygonal = is_loaded(&it.desc.mesh)
            || matches!(
                it.desc.mesh,
                MeshDesc::Stairs { .. } | MeshDesc::Grid { .. }
            );
        let displaced = g
            .displacement
            .as_ref()
            .is_some_and(|d| d.mode == DisplacementMode::True);
        if polygonal && g.approximation.is_some() && !displaced {
            let kind = kind_name(&it.desc.mesh);
            let article = if kind.starts_with(['a', 'e', 'i', 'o', 'u', 'O']) {
                "an"
            } else {
                "a"
            };
            let pos = src.pos(it.file, &it.at(".approximation"));
            let message = format!(
                "object \"{}\": the approximation has no effect on {article} {kind} without true displacement",
                it.desc.name
            );
            let ron = "leave `approximation` out: a polygon mesh is diced only for `displacement: (…, mode: True)`";
            let help = src.syntax(it.file).help_each(super::syntax::Helps {
                ron,
                mi: ron,
                rib: "a polygon is diced only under true displacement (a `Displacement` shader with `Attribute \"render\" \"truedisplacement\" [1]`): give `ShadingRate` only to the surfaces it dices (inside their `AttributeBegin`/`AttributeEnd`)",
                gltf: ron,
            });
            src.push_warning(
                it.file,
                super::diagnostics::Diagnostic::at(pos, message, Some(help)),
            );
        }
    }
}

/// Where an object's checks report: the object's name and the path of its `mesh` value.
pub(crate) struct Ctx<'a> {
    /// Object name, for messages.
    pub object: &'a str,
    /// `objects[i].mesh`.
    pub base: String,
}

/// RenderMan spelling accepted for a field (so a located error finds the written value).
fn alias(field: &str) -> Option<&'static str> {
    Some(match field {
        "r_major" => "rmajor",
        "r_minor" => "rminor",
        "phi_min" => "phimin",
        "phi_max" => "phimax",
        "theta_max" => "thetamax",
        "z_min" => "zmin",
        "z_max" => "zmax",
        _ => return None,
    })
}

/// Reports a geometry error of `what` at `{parent}.{field}` (or its alias as written; the
/// parent itself when the field is not written).
pub(crate) fn report(
    ck: &mut Checker<'_>,
    object: &str,
    what: &str,
    parent: &str,
    field: Option<&str>,
    err: &GeometryError,
) {
    let mut path = parent.to_string();
    if let Some(f) = field {
        let here = ck.src.pos(ck.file, parent);
        let direct = format!("{parent}.{f}");
        path = match alias(f) {
            Some(a) if ck.src.pos(ck.file, &direct) == here => format!("{parent}.{a}"),
            _ => direct,
        };
    }
    let mut text = tidy(err);
    if ck.src.syntax(ck.file) == super::syntax::Syntax::Rib {
        text = rib_names(&text);
    }
    ck.error(&path, format!("object \"{object}\" ({what}): {text}"));
}

/// A geometry error's text with the quadric parameters under the names of RISpec 3.2's
/// requests (`Torus majorradius minorradius phimin phimax thetamax`, `Sphere radius zmin
/// zmax thetamax`) and a displacement's bound under its `Attribute "displacementbound"`,
/// for a RIB scene.
fn rib_names(text: &str) -> String {
    [
        ("r_major", "majorradius"),
        ("r_minor", "minorradius"),
        ("phi_min", "phimin"),
        ("phi_max", "phimax"),
        ("theta_max", "thetamax"),
        ("z_min", "zmin"),
        ("z_max", "zmax"),
        ("`bound`", "`displacementbound`"),
    ]
    .iter()
    .fold(text.to_string(), |t, (ron, rib)| t.replace(ron, rib))
}

/// The error's text for a located message: values shown as written (every parameter went
/// through f32, so its shortest f32 form), without a generator prefix the message repeats.
fn tidy(err: &GeometryError) -> String {
    match err {
        GeometryError::OutOfRange {
            parameter,
            value,
            expected,
        } => {
            let shown = (*value as f32).to_string();
            GeometryError::OutOfRange {
                parameter,
                value: shown.parse().unwrap_or(*value),
                expected,
            }
            .to_string()
        }
        GeometryError::BadCount { message } => ["patch mesh: ", "nurbs: ", "subdivision mesh: "]
            .iter()
            .find_map(|p| message.strip_prefix(p))
            .unwrap_or(message)
            .to_string(),
        other => other.to_string(),
    }
}

/// A finite number that fits in f32, reported at `path` otherwise.
pub(crate) fn num(ck: &mut Checker<'_>, path: &str, what: &str, x: f64) -> Option<f32> {
    ck.finite(path, what, x).then_some(x as f32)
}

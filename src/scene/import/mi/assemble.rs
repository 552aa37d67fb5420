//! From the statements to the description: the instance tree is walked from the render
//! root (object space: transforms composed in f64; camera space: none), each camera and
//! light instance becomes a camera or light named after the instance, each object one
//! `Inline` object (per-polygon `materials` when its polygons differ) and one `Nurbs`
//! object per free-form surface (a group of them when there are several), and materials' light
//! lists are resolved against the light instances.

use std::collections::{HashMap, HashSet};
use std::f64::consts::PI;

use glam::{DAffine3, DMat3, DMat4, DVec3};

use crate::scene::camera_rotation::{near_similarity, snapped_camera_from_world, uniform_scale};

use super::super::located::{Located, LocatedProblem, Pos, Problem};
use super::model::{AreaShape, LightModel, RawCamera, RawLight, RawObject, RawScene, Space};
use super::statements::Reader;
use super::MiScene;
use crate::scene::desc::{
    CameraDesc, DisplacementDesc, DisplacementModeDesc, GroupDesc, InstanceDesc, LightDesc,
    LightKindDesc, MeshDesc, ObjectDesc, PlacementDesc, RenderDesc, ScalarDesc, SceneDesc,
    TransformDesc, M4, V3,
};
use crate::scene::suggest::closest;

/// Deepest instance-group nesting followed (cycles are found by the walk itself; this bounds
/// its recursion). Exporters write every transform node as an instgroup and an instance, so
/// a long joint chain nests deeply.
const MAX_DEPTH: usize = 1000;

struct Out {
    /// Every element name defined, including elements that failed (already reported).
    defined: HashSet<String>,
    desc: SceneDesc,
    paths: Vec<(String, Located)>,
    problems: Vec<LocatedProblem>,
}

impl Out {
    fn report(&mut self, at: &Located, problem: Problem) {
        let _ = at.pos;
        self.problems.push(LocatedProblem {
            file: at.file.clone(),
            problem: Problem {
                pos: at.pos,
                ..problem
            },
        });
    }

    fn error(&mut self, at: &Located, message: impl Into<String>) {
        self.report(at, Problem::error(Pos::default(), message));
    }

    fn unknown(&mut self, at: &Located, what: &str, name: &str, known: Vec<&str>) {
        if self.defined.contains(name) {
            return; // the element failed and was reported where it is written
        }
        let mut p = Problem::error(Pos::default(), format!("unknown {what} \"{name}\""));
        if let Some(s) = closest(name, known) {
            p = p.with_help(format!("did you mean \"{s}\"?"));
        }
        self.report(at, p);
    }
}

/// The mental ray `transform` (world → object, row vectors) as `world_from_object`.
pub fn world_from_object(m: &[f64; 16]) -> Option<DMat4> {
    // Read column by column, the row-major row-vector matrix is its transpose: the
    // column-vector `object_from_world`.
    let object_from_world = DMat4::from_cols_array(m);
    let det = object_from_world.determinant();
    // Inverted as the affine transform it is (`transform::affine` divided out `w`), so the
    // bottom row stays exactly (0, 0, 0, 1): a general 4×4 inverse of a rotation rounded to
    // 4 digits leaves (−0, 0, −0, 0.9999999999999999).
    (det.is_finite() && det.abs() > 1e-12)
        .then(|| DMat4::from(DAffine3::from_mat4(object_from_world).inverse()))
}

/// A camera's `world_from_camera` with its rotation snapped and without its uniform scale, and the camera's
/// `space_scale` (the camera-space length of one world unit: the scale of the camera
/// instance's `transform`, `None` when it does not scale). A uniform scale does not change
/// a perspective image; RIB's camera transformation drops it the same way.
fn without_uniform_scale(w: DMat4) -> (DMat4, Option<f64>) {
    // The rotation rounded to a few digits in the `transform` as written
    // (`camera_from_world`) is the rotation it rounds.
    let camera_from_world = DAffine3::from_mat4(w).inverse();
    let snapped = snapped_camera_from_world(DMat4::from(camera_from_world));
    let w = DMat4::from(DAffine3::from_mat4(snapped).inverse());
    let s = uniform_scale(DMat3::from_mat4(w));
    if s == 1.0 {
        return (w, None);
    }
    let k = 1.0 / s;
    let unscaled = DMat4::from_cols(w.x_axis * k, w.y_axis * k, w.z_axis * k, w.w_axis);
    (unscaled, Some(k))
}

fn to_m4(m: DMat4) -> M4 {
    m.transpose().to_cols_array_2d()
}

fn v3(v: DVec3) -> V3 {
    (v.x, v.y, v.z)
}

fn dv(v: V3) -> DVec3 {
    DVec3::new(v.0, v.1, v.2)
}

/// Builds the description from everything read.
pub fn assemble(reader: Reader) -> Result<MiScene, Vec<LocatedProblem>> {
    let Reader {
        raw,
        problems,
        root,
        defined,
        included,
        ..
    } = reader;
    let mut out = Out {
        defined: defined.into_keys().collect(),
        desc: SceneDesc::default(),
        paths: Vec::new(),
        problems,
    };
    build(&raw, &root, &mut out);
    if out.problems.iter().any(|p| !p.problem.warning) {
        // The warnings go with the errors (each says which it is).
        return Err(out.problems);
    }
    let warnings = out.problems;
    Ok(MiScene {
        desc: out.desc,
        paths: out.paths,
        warnings,
        read_files: included,
    })
}

fn build(raw: &RawScene, root: &Located, out: &mut Out) {
    let Some(render) = &raw.render else {
        out.report(
            root,
            Problem::error(
                Pos::default(),
                "the file has no render statement: nothing to render",
            )
            .with_help(
                "end the scene with render \"root_instgroup\" \"camera_instance\" \"options\"",
            ),
        );
        return;
    };
    let options = match raw.options.get(&render.options.0) {
        Some(o) => Some(o),
        None => {
            out.unknown(
                &render.options.1,
                "options",
                &render.options.0,
                raw.options.keys().map(String::as_str).collect(),
            );
            None
        }
    };
    let space = options.map_or(Space::Camera, |o| o.space);
    if let Some(o) = options {
        out.desc.options = Some(o.desc.clone());
        out.paths.push(("options".into(), o.at.clone()));
        o.values.extend_under("options", &mut out.paths);
    }
    let instances: HashMap<&str, usize> = raw
        .instances
        .iter()
        .enumerate()
        .map(|(i, (n, _))| (n.as_str(), i))
        .collect();
    let groups: HashMap<&str, usize> = raw
        .groups
        .iter()
        .enumerate()
        .map(|(i, (n, _))| (n.as_str(), i))
        .collect();
    let objects: HashMap<&str, usize> = raw
        .objects
        .iter()
        .enumerate()
        .map(|(i, (n, _))| (n.as_str(), i))
        .collect();
    if !groups.contains_key(render.root.0.as_str()) {
        out.unknown(
            &render.root.1,
            "instgroup",
            &render.root.0,
            groups.keys().copied().collect(),
        );
        return;
    }

    // Walk the tree: cameras and lights with their composed transforms.
    let mut walk = Walk {
        raw,
        instances: &instances,
        groups: &groups,
        space,
        cameras: Vec::new(),
        lights: Vec::new(),
        visiting: HashSet::new(),
    };
    walk.group(
        render.root.0.as_str(),
        (DMat4::IDENTITY, None),
        0,
        &render.root.1,
        out,
    );
    let (cameras, lights) = (walk.cameras, walk.lights);

    for (name, cam, w, at, matrix_at) in cameras {
        let i = out.desc.cameras.len();
        out.paths.push((format!("cameras[{i}]"), at));
        // Errors about the camera matrix point at the `transform` that made it one.
        out.paths
            .push((format!("cameras[{i}].placement.Matrix[0]"), matrix_at));
        let (w, space_scale) = without_uniform_scale(w);
        cam.values
            .extend_under(&format!("cameras[{i}]"), &mut out.paths);
        out.desc.cameras.push(CameraDesc {
            name,
            fov_y: cam.fov_y,
            resolution: cam.resolution,
            aspect: cam.aspect,
            placement: PlacementDesc::Matrix(to_m4(w)),
            outputs: cam.outputs.clone(),
            imager: None,
            lens: Vec::new(),
            atmosphere: cam.atmosphere,
            space_scale,
        });
        if out.desc.environment.is_none() {
            out.desc.environment = cam.environment.clone();
        }
    }
    let shadows = options.is_none_or(|o| o.shadows);
    for (name, light, w, at) in lights {
        match light_desc(name.clone(), light, w, shadows, &at, out) {
            Some(desc) => {
                let i = out.desc.lights.len();
                out.paths.push((format!("lights[{i}]"), at));
                light
                    .values
                    .extend_under(&format!("lights[{i}]"), &mut out.paths);
                out.desc.lights.push(desc);
            }
            None => {
                out.defined.insert(name);
            }
        }
    }
    let light_names: Vec<String> = out.desc.lights.iter().map(|l| l.name.clone()).collect();

    for (name, m) in &raw.materials {
        let mut desc = m.desc.clone();
        if let Some(list) = &m.lights {
            let mut names = Vec::new();
            for (l, at) in list {
                if light_names.contains(l) {
                    names.push(l.clone());
                } else if raw.lights.contains_key(l) {
                    out.report(
                        at,
                        Problem::error(Pos::default(), format!("material \"{name}\" lists light \"{l}\", which is not instanced under the render root"))
                            .with_help("lights lists name light instances"),
                    );
                } else {
                    out.unknown(
                        at,
                        "light instance",
                        l,
                        light_names.iter().map(String::as_str).collect(),
                    );
                }
            }
            desc.lights = Some(if m.exclusive {
                light_names
                    .iter()
                    .filter(|l| !names.contains(l))
                    .cloned()
                    .collect()
            } else {
                names
            });
        }
        let i = out.desc.materials.len();
        out.paths.push((format!("materials[{i}]"), m.at.clone()));
        m.values
            .extend_under(&format!("materials[{i}]"), &mut out.paths);
        out.desc.materials.push(desc);
    }
    let material_names: Vec<&str> = raw.materials.iter().map(|(n, _)| n.as_str()).collect();
    // `contour_shader_framefade` at the render camera's frame.
    let frame = raw
        .instances
        .iter()
        .find(|(n, _)| *n == render.camera.0)
        .and_then(|(_, i)| raw.cameras.get(&i.of))
        .map_or(0.0, |c| c.frame);
    for (m, (_, raw_m)) in out.desc.materials.iter_mut().zip(&raw.materials) {
        if let Some(f) = &raw_m.frame_fade {
            m.contour = Some(super::contours::faded(f, frame));
        }
    }

    let overridden = raw.instances.iter().any(|(_, i)| i.material.is_some());
    let displaced: HashMap<&str, &ScalarDesc> = raw
        .materials
        .iter()
        .filter_map(|(n, m)| Some((n.as_str(), m.displace.as_ref()?)))
        .collect();
    let materials = Materials {
        names: &material_names,
        displaced: &displaced,
        overridden,
    };
    for (name, obj) in &raw.objects {
        objects_of(name, obj, &materials, out);
    }
    for (name, inst) in &raw.instances {
        let placed_object = objects.contains_key(inst.of.as_str());
        let placed_group = groups.contains_key(inst.of.as_str());
        if !placed_object && !placed_group {
            let known_elsewhere =
                raw.cameras.contains_key(&inst.of) || raw.lights.contains_key(&inst.of);
            if !known_elsewhere {
                let mut known: Vec<&str> = objects.keys().copied().collect();
                known.extend(groups.keys().copied());
                known.extend(raw.cameras.keys().map(String::as_str));
                known.extend(raw.lights.keys().map(String::as_str));
                out.unknown(&inst.of_at, "element", &inst.of, known);
            }
            continue;
        }
        let transform = match (&inst.transform, space) {
            (Some(m), Space::Object) => match world_from_object(m) {
                Some(w) => vec![TransformDesc::Matrix(to_m4(w))],
                None => {
                    let at = inst.transform_at.clone().unwrap_or(inst.at.clone());
                    out.error(
                        &at,
                        format!("the transform of instance \"{name}\" is singular"),
                    );
                    continue;
                }
            },
            _ => Vec::new(),
        };
        let material = match &inst.material {
            Some((m, at)) if !material_names.contains(&m.as_str()) => {
                out.unknown(at, "material", m, material_names.clone());
                None
            }
            other => other.as_ref().map(|(m, _)| m.clone()),
        };
        let i = out.desc.instances.len();
        out.paths.push((format!("instances[{i}]"), inst.at.clone()));
        if let (false, Some(at)) = (transform.is_empty(), &inst.transform_at) {
            // The matrix as a whole (singular, beyond f32): at its first number.
            out.paths
                .push((format!("instances[{i}].transform"), at.clone()));
        }
        out.desc.instances.push(InstanceDesc {
            name: name.clone(),
            of: inst.of.clone(),
            transform,
            material,
            bake: None,
            caustic: inst.flags.caustic,
            globillum: inst.flags.globillum,
            visible: inst.flags.visible,
            shadow: inst.flags.shadow,
            trace: inst.flags.trace,
        });
    }
    for (name, g) in &raw.groups {
        let mut members = Vec::new();
        for (m, at) in &g.members {
            match instances.get(m.as_str()).map(|&i| &raw.instances[i].1) {
                Some(inst)
                    if objects.contains_key(inst.of.as_str())
                        || groups.contains_key(inst.of.as_str()) =>
                {
                    members.push(m.clone())
                }
                Some(_) => {}
                None => out.unknown(at, "instance", m, instances.keys().copied().collect()),
            }
        }
        let i = out.desc.groups.len();
        out.paths.push((format!("groups[{i}]"), g.at.clone()));
        out.desc.groups.push(GroupDesc {
            name: name.clone(),
            members,
        });
    }
    if !out.desc.cameras.iter().any(|c| c.name == render.camera.0) {
        let known: Vec<String> = out.desc.cameras.iter().map(|c| c.name.clone()).collect();
        let known = known.iter().map(String::as_str).collect();
        out.unknown(&render.camera.1, "camera instance", &render.camera.0, known);
    }
    out.paths.push(("render".into(), render.at.clone()));
    out.desc.render = Some(RenderDesc {
        root: render.root.0.clone(),
        camera: render.camera.0.clone(),
    });
}

/// The stagelight objects of one `.mi` object: its polygons (one `Inline` object) and each
/// free-form surface (one `Nurbs` object). One part keeps the object's name; several
/// become a group of that name holding one object and one instance per part, both named
/// `<object>.<surface>` (`<object>.polygons` for the polygons), so instances of the object
/// place every part.
/// What object building needs of the materials.
struct Materials<'a> {
    /// Every material name.
    names: &'a [&'a str],
    /// The displacement of each material that has one (`displace "myDisplacement"`).
    displaced: &'a HashMap<&'a str, &'a ScalarDesc>,
    /// Whether any instance overrides materials.
    overridden: bool,
}

impl Materials<'_> {
    /// The displacement of objects drawn in material `m`.
    fn displacement(&self, m: Option<&str>) -> Option<DisplacementDesc> {
        let shader = (*self.displaced.get(m?)?).clone();
        Some(DisplacementDesc {
            shader,
            bound: None,
            mode: DisplacementModeDesc::True,
        })
    }
}

fn objects_of(name: &str, obj: &RawObject, materials: &Materials<'_>, out: &mut Out) {
    let parts = usize::from(!obj.polygons.is_empty()) + obj.surfaces.len();
    let part_name = |part: &str| {
        if parts == 1 {
            name.to_string()
        } else {
            format!("{name}.{part}")
        }
    };
    let mut members = Vec::new();
    if !obj.polygons.is_empty() {
        let object = part_name("polygons");
        if polygons_of(&object, obj, materials, out) {
            members.push(object);
        }
    }
    for s in &obj.surfaces {
        if let (Some(m), Some(at)) = (&s.material, &s.material_at) {
            if !materials.names.contains(&m.as_str()) {
                out.unknown(at, "material", m, materials.names.to_vec());
                continue;
            }
        }
        let object = part_name(&s.name);
        let i = out.desc.objects.len();
        out.paths.push((format!("objects[{i}]"), s.at.clone()));
        out.desc.objects.push(ObjectDesc {
            name: object.clone(),
            mesh: MeshDesc::Nurbs {
                degree_u: s.u.degree,
                degree_v: s.v.degree,
                count_u: s.u.count,
                count_v: s.v.count,
                knots_u: s.u.knots.clone(),
                knots_v: s.v.knots.clone(),
                points: s.points.clone(),
                variables: Default::default(),
            },
            material: s.material.clone(),
            approximation: s.approximation.clone(),
            displacement: materials.displacement(s.material.as_deref()),
            derivatives: false,
            reverse_orientation: false,
            caustic: obj.flags.caustic,
            globillum: obj.flags.globillum,
            visible: obj.flags.visible,
            shadow: obj.flags.shadow,
            trace: obj.flags.trace,
            label: obj.flags.label,
        });
        members.push(object);
    }
    if parts < 2 {
        return;
    }
    for m in &members {
        let i = out.desc.instances.len();
        out.paths.push((format!("instances[{i}]"), obj.at.clone()));
        out.desc
            .instances
            .push(InstanceDesc::plain(m, m, Vec::new()));
    }
    let i = out.desc.groups.len();
    out.paths.push((format!("groups[{i}]"), obj.at.clone()));
    out.desc.groups.push(GroupDesc {
        name: name.to_string(),
        members,
    });
}

/// The `Inline` object `object` of the polygons of `obj`. Polygons that all name one
/// material give the object that material; otherwise (several materials, polygons without
/// one, or a scene whose instances override materials, which in mental ray reach only
/// polygons without a material of their own) each polygon names its own in `materials`
/// (`""`: the inherited one). False when a material is unknown (reported).
fn polygons_of(object: &str, obj: &RawObject, materials: &Materials<'_>, out: &mut Out) -> bool {
    let overridden = materials.overridden;
    let mut order: Vec<Option<&str>> = Vec::new();
    for p in &obj.polygons {
        let m = p.material.as_deref();
        if let Some(m) = m {
            if !materials.names.contains(&m) {
                out.unknown(&p.at, "material", m, materials.names.to_vec());
                return false;
            }
        }
        if !order.contains(&m) {
            order.push(m);
        }
    }
    let per_polygon = order.len() > 1 || (overridden && order.iter().any(Option::is_some));
    let (material, polygon_materials) = if per_polygon {
        let names: Vec<String> = obj
            .polygons
            .iter()
            .map(|p| p.material.clone().unwrap_or_default())
            .collect();
        (None, Some(names))
    } else {
        (order.first().copied().flatten().map(str::to_string), None)
    };
    // Displacement is per object: it needs one material (mental ray displaces per material).
    let displacement = match &polygon_materials {
        None => materials.displacement(material.as_deref()),
        Some(names) => {
            if let Some(m) = names
                .iter()
                .find(|m| materials.displaced.contains_key(m.as_str()))
            {
                out.report(
                    &obj.at,
                    Problem::warning(
                        Pos::default(),
                        format!("object \"{object}\" is not displaced: the displacement of material \"{m}\" applies to whole objects, and its polygons have several materials"),
                    ),
                );
            }
            None
        }
    };
    let i = out.desc.objects.len();
    out.paths.push((format!("objects[{i}]"), obj.at.clone()));
    out.desc.objects.push(ObjectDesc {
        name: object.to_string(),
        mesh: MeshDesc::Inline {
            vertices: obj.vertices.clone(),
            polygons: obj.polygons.iter().map(|p| p.vertices.clone()).collect(),
            normals: None,
            // The `t` references, when every vertex has one.
            uvs: obj.uvs.iter().copied().collect::<Option<Vec<_>>>(),
            materials: polygon_materials,
        },
        material,
        // Polygons are diced only when displaced.
        approximation: displacement.as_ref().and(obj.approximation.clone()),
        displacement,
        derivatives: false,
        reverse_orientation: false,
        caustic: obj.flags.caustic,
        globillum: obj.flags.globillum,
        visible: obj.flags.visible,
        shadow: obj.flags.shadow,
        trace: obj.flags.trace,
        label: obj.flags.label,
    });
    true
}

/// A camera or light placed by the walk: instance name, element, `world_from_object`, where.
type Placed<'a, T> = (String, &'a T, DMat4, Located);

/// A camera placed by the walk, and where its matrix is written: the `transform` after
/// which the composed matrix stopped being a camera's (a rotation and uniform scale), else
/// the camera instance's own `transform` (or the instance).
type PlacedCamera<'a> = (String, &'a RawCamera, DMat4, Located, Located);

/// A composed `world_from_object` and the `transform` after which it stopped being a
/// camera's (`None` while it is one).
type Composed<'a> = (DMat4, Option<&'a Located>);

/// Whether `w` can place a camera: a rotation (within the rounding the camera validation
/// snaps) times a uniform scale, not mirrored.
fn camera_like(w: DMat4) -> bool {
    let l = DMat3::from_mat4(w);
    near_similarity(l) && l.determinant() > 0.0
}

struct Walk<'a> {
    raw: &'a RawScene,
    instances: &'a HashMap<&'a str, usize>,
    groups: &'a HashMap<&'a str, usize>,
    space: Space,
    cameras: Vec<PlacedCamera<'a>>,
    lights: Vec<Placed<'a, RawLight>>,
    visiting: HashSet<String>,
}

impl<'a> Walk<'a> {
    fn group(
        &mut self,
        name: &str,
        parent: Composed<'a>,
        depth: usize,
        at: &Located,
        out: &mut Out,
    ) {
        if depth > MAX_DEPTH {
            out.error(
                at,
                format!(
                    "instgroup \"{name}\" is nested more than {MAX_DEPTH} instance groups deep"
                ),
            );
            return;
        }
        if !self.visiting.insert(name.to_string()) {
            out.error(at, format!("instgroup \"{name}\" contains itself"));
            return;
        }
        let g = &self.raw.groups[self.groups[name]].1;
        for (member, m_at) in &g.members {
            let Some(&i) = self.instances.get(member.as_str()) else {
                continue; // reported with the groups
            };
            let (iname, inst) = (&self.raw.instances[i].0, &self.raw.instances[i].1);
            let local = match (&inst.transform, self.space) {
                (Some(m), Space::Object) => world_from_object(m).unwrap_or(DMat4::IDENTITY),
                _ => DMat4::IDENTITY,
            };
            let w = parent.0 * local;
            let non_camera_at = match parent.1 {
                _ if camera_like(w) => None,
                Some(at) => Some(at),
                None => inst.transform_at.as_ref(),
            };
            if let Some(cam) = self.raw.cameras.get(&inst.of) {
                let matrix_at = non_camera_at.or(inst.transform_at.as_ref());
                let matrix_at = matrix_at.unwrap_or(&inst.at).clone();
                self.cameras
                    .push((iname.clone(), cam, w, inst.at.clone(), matrix_at));
            } else if let Some(light) = self.raw.lights.get(&inst.of) {
                let name = if self.lights.iter().any(|l| &l.0 == iname) {
                    format!("{iname}#{}", self.lights.len())
                } else {
                    iname.clone()
                };
                self.lights.push((name, light, w, inst.at.clone()));
            } else if self.groups.contains_key(inst.of.as_str()) {
                self.group(&inst.of, (w, non_camera_at), depth + 1, m_at, out);
            }
        }
        self.visiting.remove(name);
    }
}

/// The light `light` placed by `w`.
fn light_desc(
    name: String,
    light: &RawLight,
    w: DMat4,
    shadows: bool,
    at: &Located,
    out: &mut Out,
) -> Option<LightDesc> {
    let origin = light.origin.map(|o| w.transform_point3(dv(o)));
    let direction = light.direction.map(|d| w.transform_vector3(dv(d)));
    let physical = light.inverse_square;
    let mut color = light.color;
    let mut samples = None;
    let scale = |c: V3, k: f64| (c.0 * k, c.1 * k, c.2 * k);
    let kind = if let Some((shape, n)) = light.area {
        let o = origin.unwrap_or(w.transform_point3(DVec3::ZERO));
        samples = Some(n.max(1));
        let (kind, area) = match shape {
            AreaShape::Rectangle(e, f) => {
                let (e, f) = (w.transform_vector3(dv(e)), w.transform_vector3(dv(f)));
                let kind = LightKindDesc::Rect {
                    corner: v3(o - 0.5 * (e + f)),
                    edge_u: v3(e),
                    edge_v: v3(f),
                };
                (kind, e.cross(f).length())
            }
            AreaShape::Disc(n, r) => (
                LightKindDesc::Disc {
                    center: v3(o),
                    normal: v3(w.transform_vector3(dv(n))),
                    radius: r,
                },
                PI * r * r,
            ),
            AreaShape::Sphere(r) => (
                LightKindDesc::Sphere {
                    center: v3(o),
                    radius: r,
                },
                4.0 * PI * r * r,
            ),
            AreaShape::Cylinder(a, r) => {
                let a = w.transform_vector3(dv(a));
                (
                    LightKindDesc::Cylinder {
                        start: v3(o - 0.5 * a),
                        end: v3(o + 0.5 * a),
                        radius: r,
                    },
                    2.0 * PI * r * a.length(),
                )
            }
        };
        // A physical light's area shape emits the same power as its point light; on a
        // non-physical shader (`mib_light_point`, `mib_light_spot`) each light sample is a
        // point light of this colour on the shape, without falloff, and the samples are
        // averaged (seed 001, §3.2.2: "you have to divide by the number of samples").
        if physical && area > 0.0 {
            color = scale(color, 1.0 / (PI * area));
        }
        if !physical && light.visible {
            out.report(
                at,
                Problem::warning(
                    Pos::default(),
                    format!("light \"{name}\": `visible` is not drawn: an area shape on a light shader without distance falloff lights the scene as point lights spread over the shape, which rays do not meet (use `physical_light` for a visible area light)"),
                ),
            );
        }
        kind
    } else {
        let distant = light.model == LightModel::Infinite || origin.is_none();
        match (origin, direction, light.spread) {
            (_, Some(d), _) if distant => LightKindDesc::Directional { direction: v3(d) },
            (Some(p), Some(d), Some(spread)) => {
                if !(-1.0..1.0).contains(&spread) || spread < 0.0 {
                    let spread_at = light.values.get(".kind.Spot.cone_angle").unwrap_or(at);
                    out.error(spread_at, format!("light \"{name}\": spread must be the cosine of the cone, in [0, 1), found {spread}"));
                    return None;
                }
                let outer = spread.acos().to_degrees();
                let inner = match light.model {
                    LightModel::Spot { cone: Some(c) } if c > spread => {
                        c.min(1.0).acos().to_degrees()
                    }
                    _ => outer,
                };
                if physical {
                    color = scale(color, 1.0 / (4.0 * PI));
                }
                LightKindDesc::Spot {
                    position: v3(p),
                    target: v3(p + d),
                    cone_angle: outer,
                    penumbra: outer - inner,
                    beam_distribution: 0.0,
                }
            }
            (Some(p), _, _) => {
                if light.model == LightModel::Infinite {
                    out.error(
                        at,
                        format!("light \"{name}\": an infinite light needs a direction"),
                    );
                    return None;
                }
                if physical {
                    color = scale(color, 1.0 / (4.0 * PI));
                }
                LightKindDesc::Point { position: v3(p) }
            }
            (None, _, _) => {
                out.error(
                    at,
                    format!("light \"{name}\" has neither origin nor direction"),
                );
                return None;
            }
        }
    };
    let is_delta = !matches!(
        kind,
        LightKindDesc::Rect { .. }
            | LightKindDesc::Disc { .. }
            | LightKindDesc::Sphere { .. }
            | LightKindDesc::Cylinder { .. }
    );
    let directional = matches!(kind, LightKindDesc::Directional { .. });
    Some(LightDesc {
        name,
        kind,
        color,
        intensity: 1.0,
        shadows: shadows && light.shadows,
        shadow_factor: if shadows && light.shadows {
            light.shadow_factor
        } else {
            0.0
        },
        samples,
        visible: light.visible && !is_delta && physical,
        attenuation: if directional { None } else { light.attenuation },
        // Area shapes follow the shader too: without falloff, point lights over the shape.
        inverse_square: physical || directional,
        energy: light.energy,
        caustic_photons: light.caustic_photons,
        globillum_photons: light.globillum_photons,
    })
}

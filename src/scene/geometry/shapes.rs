//! Geometry shaders, parametric surfaces and subdivision meshes: values checked where they
//! are written, then validated by the geometry code itself.

use glam::{Vec3, Vec4};

use super::{num, report, Ctx, Generated};
use crate::components::{
    Cone, CubicBasis, Cylinder, Disk, Grid, NurbsSurface, PatchKind, PatchMesh, Procedural, Sphere,
    Stairs, SubdivMesh, Surface, SurfaceValues, SurfaceVariables, Torus,
};
use crate::procedural;
use crate::scene::desc::{BasisDesc, MeshDesc, SurfaceValuesDesc, SurfaceVariablesDesc, V3};
use crate::scene::mesh_load;
use crate::scene::validate::Checker;
use crate::tessellation::nurbs::NurbsSource;
use crate::tessellation::patch::PatchMeshSource;
use crate::tessellation::{subdiv, variables, GeometryError, PatchSource};

/// Checks a generated mesh description (not `Obj`, `Inline` or `Scatter`) and builds its
/// component.
pub fn generator(ck: &mut Checker<'_>, ctx: &Ctx<'_>, mesh: &MeshDesc) -> Option<Generated> {
    match mesh {
        MeshDesc::PatchMesh {
            basis,
            nu,
            nv,
            u_wrap,
            v_wrap,
            points,
            variables,
        } => {
            let at = format!("{}.PatchMesh", ctx.base);
            let points = control_points(ck, &format!("{at}.points"), points)?;
            let vars = surface_variables(ck, &at, variables)?;
            let mesh = PatchMesh {
                kind: match basis {
                    BasisDesc::Bilinear => PatchKind::Bilinear,
                    BasisDesc::Bezier => PatchKind::Bicubic(CubicBasis::Bezier),
                    BasisDesc::BSpline => PatchKind::Bicubic(CubicBasis::BSpline),
                    BasisDesc::CatmullRom => PatchKind::Bicubic(CubicBasis::CatmullRom),
                },
                nu: *nu,
                nv: *nv,
                u_wrap: *u_wrap,
                v_wrap: *v_wrap,
                points,
                vars,
            };
            let checked = PatchMeshSource::new(&mesh).and_then(|src| {
                let corners = 4 * src.patch_count();
                variables::check(&mesh.vars, mesh.points.len(), corners, "patch mesh")
            });
            if let Err(e) = checked {
                let field = match &e {
                    GeometryError::BadCount { message } if message.contains(": u:") => "nu",
                    GeometryError::BadCount { message } if message.contains(": v:") => "nv",
                    GeometryError::BadCount { message } if message.contains(": s:") => {
                        "variables.s"
                    }
                    GeometryError::BadCount { message } if message.contains(": t:") => {
                        "variables.t"
                    }
                    GeometryError::BadCount { message } if message.contains(": normals:") => {
                        "variables.normals"
                    }
                    _ => "points",
                };
                report(ck, ctx.object, "patch mesh", &at, Some(field), &e);
                return None;
            }
            Some(Generated::Surface(Surface::Patches(mesh)))
        }
        MeshDesc::Nurbs {
            degree_u,
            degree_v,
            count_u,
            count_v,
            knots_u,
            knots_v,
            points,
            variables,
        } => {
            let at = format!("{}.Nurbs", ctx.base);
            let vars = surface_variables(ck, &at, variables)?;
            let mut ok = true;
            let mut knots = |ck: &mut Checker<'_>, name: &str, ks: &[f64]| -> Vec<f32> {
                ks.iter()
                    .enumerate()
                    .map(|(k, &x)| {
                        let v = num(ck, &format!("{at}.{name}[{k}]"), "knot", x);
                        ok &= v.is_some();
                        v.unwrap_or(0.0)
                    })
                    .collect()
            };
            let knots_u = knots(ck, "knots_u", knots_u);
            let knots_v = knots(ck, "knots_v", knots_v);
            let mut pts = Vec::with_capacity(points.len());
            for (k, p) in points.iter().enumerate() {
                let path = format!("{at}.points[{k}]");
                let c = [p.0, p.1, p.2, p.3];
                let v: Vec<Option<f32>> = c
                    .iter()
                    .enumerate()
                    .map(|(i, &x)| num(ck, &format!("{path}[{i}]"), "control point", x))
                    .collect();
                match v[..] {
                    [Some(x), Some(y), Some(z), Some(w)] => pts.push(Vec4::new(x, y, z, w)),
                    _ => ok = false,
                }
            }
            if !ok {
                return None;
            }
            let surface = NurbsSurface {
                degree_u: *degree_u,
                degree_v: *degree_v,
                count_u: *count_u,
                count_v: *count_v,
                knots_u,
                knots_v,
                points: pts,
                vars,
            };
            let checked = NurbsSource::new(&surface).and_then(|_| {
                let corners = 4 * NurbsSource::segments(&surface);
                variables::check(&surface.vars, surface.points.len(), corners, "nurbs")
            });
            if let Err(e) = checked {
                let field = match &e {
                    GeometryError::BadCount { message } if message.starts_with("nurbs: s:") => {
                        "variables.s".into()
                    }
                    GeometryError::BadCount { message } if message.starts_with("nurbs: t:") => {
                        "variables.t".into()
                    }
                    GeometryError::BadCount { message }
                        if message.starts_with("nurbs: normals:") =>
                    {
                        "variables.normals".into()
                    }
                    GeometryError::BadCount { message } => {
                        let dir = if message.contains(": v:") { "v" } else { "u" };
                        if message.contains("control points") {
                            format!("count_{dir}")
                        } else if message.contains("knots") || message.contains("domain") {
                            format!("knots_{dir}")
                        } else {
                            "points".into()
                        }
                    }
                    GeometryError::OutOfRange { parameter, .. } if *parameter != "weight" => {
                        parameter.to_string()
                    }
                    GeometryError::OutOfRange { .. } => {
                        match surface.points.iter().position(|p| p.w <= 0.0) {
                            Some(k) => format!("points[{k}][3]"),
                            None => "points".into(),
                        }
                    }
                    _ => "points".into(),
                };
                report(ck, ctx.object, "nurbs", &at, Some(&field), &e);
                return None;
            }
            Some(Generated::Surface(Surface::Nurbs(surface)))
        }
        MeshDesc::Subdiv {
            vertices,
            polygons,
            variables,
        } => {
            let at = format!("{}.Subdiv", ctx.base);
            if !mesh_load::check_inline(ck, &at, vertices, polygons, None, None) {
                return None;
            }
            let vars = surface_variables(ck, &at, variables)?;
            let corners = polygons.iter().map(Vec::len).sum();
            if let Err(e) = variables::check(&vars, vertices.len(), corners, "subdivision mesh") {
                report(ck, ctx.object, "subdiv", &at, Some("variables"), &e);
                return None;
            }
            let mesh = SubdivMesh {
                positions: vertices
                    .iter()
                    .map(|v| Vec3::new(v.0 as f32, v.1 as f32, v.2 as f32))
                    .collect(),
                face_sizes: polygons.iter().map(|p| p.len() as u32).collect(),
                face_indices: polygons.iter().flatten().copied().collect(),
                vars,
            };
            // One level of refinement finds non-manifold edges.
            let one_level = crate::components::Approximation {
                technique: crate::components::Technique::Parametric { u: 1, v: 1 },
                min_subdiv: 0,
                max_subdiv: 1,
            };
            if let Err(e) = subdiv::limit_cage(&mesh, &one_level) {
                report(ck, ctx.object, "subdiv", &at, Some("polygons"), &e);
                return None;
            }
            Some(Generated::Subdiv(mesh))
        }
        other => procedural_shape(ck, ctx, other).map(Generated::Procedural),
    }
}

/// The user texture coordinates and normals of a surface (each value not finite reported
/// at `at.variables.<name>…[k]`).
fn surface_variables(
    ck: &mut Checker<'_>,
    at: &str,
    vars: &SurfaceVariablesDesc,
) -> Option<SurfaceVariables> {
    let mut ok = true;
    let mut values = |name: &str, v: &SurfaceValuesDesc<Vec3>| -> SurfaceValues {
        let (variant, list) = match v {
            SurfaceValuesDesc::Control(l) => ("Control", l),
            SurfaceValuesDesc::Corners(l) => ("Corners", l),
        };
        if let Some(k) = list.iter().position(|x| !x.is_finite()) {
            ck.error(
                &format!("{at}.variables.{name}.{variant}[{k}]"),
                format!("{name} values must be finite numbers"),
            );
            ok = false;
        }
        match v {
            SurfaceValuesDesc::Control(_) => SurfaceValues::Control(list.clone()),
            SurfaceValuesDesc::Corners(_) => SurfaceValues::Corners(list.clone()),
        }
    };
    let scalar = |v: &SurfaceValuesDesc<f64>| -> SurfaceValuesDesc<Vec3> {
        let map = |l: &Vec<f64>| l.iter().map(|&x| Vec3::new(x as f32, 0.0, 0.0)).collect();
        match v {
            SurfaceValuesDesc::Control(l) => SurfaceValuesDesc::Control(map(l)),
            SurfaceValuesDesc::Corners(l) => SurfaceValuesDesc::Corners(map(l)),
        }
    };
    let vector = |v: &SurfaceValuesDesc<V3>| -> SurfaceValuesDesc<Vec3> {
        let map = |l: &Vec<V3>| {
            l.iter()
                .map(|p| Vec3::new(p.0 as f32, p.1 as f32, p.2 as f32))
                .collect()
        };
        match v {
            SurfaceValuesDesc::Control(l) => SurfaceValuesDesc::Control(map(l)),
            SurfaceValuesDesc::Corners(l) => SurfaceValuesDesc::Corners(map(l)),
        }
    };
    let out = SurfaceVariables {
        s: vars.s.as_ref().map(|v| values("s", &scalar(v))),
        t: vars.t.as_ref().map(|v| values("t", &scalar(v))),
        normals: vars.normals.as_ref().map(|v| values("normals", &vector(v))),
    };
    ok.then_some(out)
}

/// Finite control points (each bad coordinate reported at `path[k][c]`).
fn control_points(
    ck: &mut Checker<'_>,
    path: &str,
    points: &[crate::scene::desc::V3],
) -> Option<Vec<Vec3>> {
    let mut ok = true;
    let out: Vec<Vec3> = points
        .iter()
        .enumerate()
        .map(
            |(k, p)| match ck.v3(&format!("{path}[{k}]"), "control point", *p) {
                Some(v) => v.as_vec3(),
                None => {
                    ok = false;
                    Vec3::ZERO
                }
            },
        )
        .collect();
    ok.then_some(out)
}

/// The geometry shaders (`Procedural`), validated by `procedural::validate`.
fn procedural_shape(ck: &mut Checker<'_>, ctx: &Ctx<'_>, mesh: &MeshDesc) -> Option<Procedural> {
    let variant = match mesh {
        MeshDesc::Sphere { .. } => "Sphere",
        MeshDesc::Cylinder { .. } => "Cylinder",
        MeshDesc::Cone { .. } => "Cone",
        MeshDesc::Disk { .. } => "Disk",
        MeshDesc::Torus { .. } => "Torus",
        MeshDesc::Stairs { .. } => "Stairs",
        MeshDesc::Grid { .. } => "Grid",
        _ => return None,
    };
    let at = format!("{}.{variant}", ctx.base);
    let mut ok = true;
    let mut f = |ck: &mut Checker<'_>, field: &str, x: f64| -> f32 {
        let v = num(ck, &format!("{at}.{field}"), field, x);
        ok &= v.is_some();
        v.unwrap_or(0.0)
    };
    let p = match *mesh {
        MeshDesc::Sphere {
            radius,
            z_min,
            z_max,
            theta_max,
        } => Procedural::Sphere(Sphere {
            radius: f(ck, "radius", radius),
            // Unwritten bounds follow the radius; a bad radius is reported once, not again
            // through bounds the user never wrote.
            z_min: f(ck, "z_min", z_min.unwrap_or(-finite_or_one(radius))),
            z_max: f(ck, "z_max", z_max.unwrap_or(finite_or_one(radius))),
            theta_max: f(ck, "theta_max", theta_max),
        }),
        MeshDesc::Cylinder {
            radius,
            z_min,
            z_max,
            theta_max,
        } => Procedural::Cylinder(Cylinder {
            radius: f(ck, "radius", radius),
            z_min: f(ck, "z_min", z_min),
            z_max: f(ck, "z_max", z_max),
            theta_max: f(ck, "theta_max", theta_max),
        }),
        MeshDesc::Cone {
            height,
            radius,
            theta_max,
        } => Procedural::Cone(Cone {
            height: f(ck, "height", height),
            radius: f(ck, "radius", radius),
            theta_max: f(ck, "theta_max", theta_max),
        }),
        MeshDesc::Disk {
            height,
            radius,
            theta_max,
        } => Procedural::Disk(Disk {
            height: f(ck, "height", height),
            radius: f(ck, "radius", radius),
            theta_max: f(ck, "theta_max", theta_max),
        }),
        MeshDesc::Torus {
            r_major,
            r_minor,
            phi_min,
            phi_max,
            theta_max,
        } => Procedural::Torus(Torus {
            r_major: f(ck, "r_major", r_major),
            r_minor: f(ck, "r_minor", r_minor),
            phi_min: f(ck, "phi_min", phi_min),
            phi_max: f(ck, "phi_max", phi_max),
            theta_max: f(ck, "theta_max", theta_max),
        }),
        MeshDesc::Stairs {
            steps,
            width,
            depth,
            height,
            closed,
        } => Procedural::Stairs(Stairs {
            steps,
            width: f(ck, "width", width),
            depth: f(ck, "depth", depth),
            height: f(ck, "height", height),
            closed,
        }),
        MeshDesc::Grid {
            size_x,
            size_y,
            nx,
            ny,
        } => Procedural::Grid(Grid {
            size_x: f(ck, "size_x", size_x),
            size_y: f(ck, "size_y", size_y),
            nx,
            ny,
        }),
        _ => return None,
    };
    if !ok {
        return None;
    }
    // Counts are clamped, never invalid: validate stairs and grids with one cell so that a
    // large mesh is not built twice.
    let probe = match p {
        Procedural::Stairs(s) => Procedural::Stairs(Stairs { steps: 1, ..s }),
        Procedural::Grid(g) => Procedural::Grid(Grid { nx: 1, ny: 1, ..g }),
        other => other,
    };
    if let Err(e) = procedural::validate(&probe) {
        let field = match &e {
            GeometryError::NotFinite { parameter }
            | GeometryError::OutOfRange { parameter, .. } => Some(*parameter),
            _ => None,
        };
        report(ck, ctx.object, p.kind(), &at, field, &e);
        return None;
    }
    Some(p)
}

/// `x` when finite, else 1 (a stand-in default after `x` itself was reported).
fn finite_or_one(x: f64) -> f64 {
    if x.is_finite() {
        x
    } else {
        1.0
    }
}

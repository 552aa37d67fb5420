//! The instance DAG: instance transforms, cycle detection, and flattening from the render
//! root into leaves (one per path from the root to an object).
//!
//! Edges go group → member instance → the group or object it places. An instance's
//! transform list applies in listed order (`[Scale, Rotate, Translate]` scales first), so
//! its matrix is `Tₙ ⋯ T₂ T₁`. Along a path the outer instance applies last:
//! `world_from_object = I_root ⋯ I_inner`, composed in f64 and rounded to f32 once.

use glam::{Affine3A, DAffine3, DVec3};

use super::desc::TransformDesc;
use super::diagnostics::Sources;
use super::names::{Resolved, Target};
use super::photon_flags::{instance_flags, object_flags};
use super::ray_flags::{instance_ray_flags, object_ray_flags};
use super::validate::{Checker, Merged};
use crate::components::{PhotonFlags, RayFlags};

/// Most placements (instances visited along all paths) a scene may expand to: a guard
/// against exponential sharing of groups.
pub const MAX_PLACEMENTS: usize = 10_000_000;

/// One placed object: a path from the root group to an object.
#[derive(Debug, Clone)]
pub struct Leaf {
    /// `root/instance/…/instance`.
    pub path: String,
    /// Innermost instance (index into `Merged::instances`).
    pub instance: usize,
    /// The object (index into `Merged::objects`).
    pub object: usize,
    /// Composed transform, rounded to f32 (in render space once [`super::rebase`] has run).
    pub world_from_object: Affine3A,
    /// Composed transform in f64 world space, including the object's mesh offset.
    pub world: DAffine3,
    /// Material from the closest instance override on the path, then the object's.
    pub material: Option<usize>,
    /// Photon flags: each from the closest instance on the path that sets it, then the
    /// object's (see [`super::photon_flags`]).
    pub photon: PhotonFlags,
    /// Ray flags (`visible`, `shadow`, `trace`), inherited as `photon` is (see
    /// [`super::ray_flags`]).
    pub rays: RayFlags,
}

/// Each instance's own transform (`None` where it is invalid).
pub fn instance_transforms(src: &mut Sources, m: &Merged<'_>) -> Vec<Option<DAffine3>> {
    m.instances
        .iter()
        .map(|it| {
            let mut ck = Checker { src, file: it.file };
            let mut total = Some(DAffine3::IDENTITY);
            for (k, t) in it.desc.transform.iter().enumerate() {
                let path = it.at(&format!(".transform[{k}]"));
                let step = transform(&mut ck, &path, t);
                total = match (total, step) {
                    (Some(total), Some(step)) => Some(step * total),
                    _ => None,
                };
            }
            let total = total?;
            let finite = total.matrix3.is_finite() && total.translation.is_finite();
            let det = total.matrix3.determinant();
            if !finite || det == 0.0 || !det.is_finite() {
                ck.error(
                    &it.at(".transform"),
                    "the composed transform overflows or is not invertible",
                );
                return None;
            }
            Some(total)
        })
        .collect()
}

/// What to write instead of a scale with a zero factor.
const SCALE_HELP: &str = "every factor must be non-zero: 1 keeps an axis as it is, and a thin \
     object takes a small factor such as 0.001 (a negative factor mirrors)";

/// What to write instead of a zero rotation axis (only RON writes `Rotate`).
const AXIS_HELP: &str =
    "the axis is the direction to turn about: `axis: (0, 1, 0)` turns about y, `(1, 0, 0)` about x";

/// What a singular matrix does wrong (RON's `Matrix`, a RIB transformation): format-neutral.
const SINGULAR_HELP: &str = "the matrix flattens space onto a plane, a line or a point (a scale \
     of 0, or two axes mapped to the same direction): every axis must keep a non-zero length \
     and a direction of its own";

fn transform(ck: &mut Checker<'_>, path: &str, t: &TransformDesc) -> Option<DAffine3> {
    match t {
        TransformDesc::Scale(s) => {
            let s = ck.v3(&format!("{path}.Scale[0]"), "scale", *s)?;
            if s.x == 0.0 || s.y == 0.0 || s.z == 0.0 {
                ck.src.error(
                    ck.file,
                    path,
                    format!(
                        "scale ({}, {}, {}) has a zero component: the transform is not \
                         invertible",
                        s.x, s.y, s.z
                    ),
                    Some(SCALE_HELP.into()),
                );
                return None;
            }
            Some(DAffine3::from_scale(s))
        }
        TransformDesc::Rotate { axis, degrees } => {
            let a = ck.v3(&format!("{path}.Rotate.axis"), "axis", *axis);
            let ok = ck.finite(&format!("{path}.Rotate.degrees"), "degrees", *degrees);
            let a = a?.normalize_or_zero();
            if a == DVec3::ZERO {
                ck.src.error(
                    ck.file,
                    &format!("{path}.Rotate.axis"),
                    "rotation axis must not be zero",
                    Some(AXIS_HELP.into()),
                );
                return None;
            }
            ok.then(|| DAffine3::from_axis_angle(a, degrees.to_radians()))
        }
        TransformDesc::Translate(v) => Some(DAffine3::from_translation(ck.v3(
            &format!("{path}.Translate[0]"),
            "translation",
            *v,
        )?)),
        TransformDesc::Matrix(m) => {
            let a = ck.affine(&format!("{path}.Matrix[0]"), "transform matrix", m)?;
            if super::desc_values::is_singular(&a.matrix3) {
                let det = a.matrix3.determinant();
                ck.src.error(
                    ck.file,
                    path,
                    format!("transform matrix is singular (determinant {det}): not invertible"),
                    Some(SINGULAR_HELP.into()),
                );
                return None;
            }
            Some(a)
        }
    }
}

/// Reports every cycle of the instance graph, at the `of` that closes it. Returns whether
/// the graph is acyclic.
pub fn check_cycles(src: &mut Sources, m: &Merged<'_>, r: &Resolved) -> bool {
    #[derive(Clone, Copy, PartialEq)]
    enum Mark {
        New,
        Open,
        Done,
    }
    let mut mark = vec![Mark::New; m.groups.len()];
    let mut acyclic = true;
    for start in 0..m.groups.len() {
        if mark[start] != Mark::New {
            continue;
        }
        // Explicit stack: (group, next member position); `trail` is the path of instances.
        let mut stack: Vec<(usize, usize)> = vec![(start, 0)];
        let mut trail: Vec<usize> = Vec::new();
        mark[start] = Mark::Open;
        while let Some(&mut (g, ref mut next)) = stack.last_mut() {
            let Some(&inst) = r.group_members[g].get(*next) else {
                mark[g] = Mark::Done;
                stack.pop();
                trail.pop();
                continue;
            };
            *next += 1;
            let Some(Target::Group(child)) = r.instance_of[inst] else {
                continue;
            };
            match mark[child] {
                Mark::New => {
                    mark[child] = Mark::Open;
                    stack.push((child, 0));
                    trail.push(inst);
                }
                Mark::Open => {
                    acyclic = false;
                    let from = stack.iter().position(|&(sg, _)| sg == child).unwrap_or(0);
                    let mut names = Vec::new();
                    for (k, &(sg, _)) in stack.iter().enumerate().skip(from) {
                        names.push(m.groups[sg].desc.name.as_str());
                        let via = if k + 1 < stack.len() { trail[k] } else { inst };
                        names.push(m.instances[via].desc.name.as_str());
                    }
                    names.push(m.groups[child].desc.name.as_str());
                    let it = &m.instances[inst];
                    src.error(
                        it.file,
                        &it.at(".of"),
                        format!("instance cycle: {}", cycle_names(&names)),
                        Some(
                            "a group may not contain itself, directly or through instances".into(),
                        ),
                    );
                }
                Mark::Done => {}
            }
        }
    }
    acyclic
}

/// Most names a cycle message lists in full; longer cycles show their first and last few.
const CYCLE_NAMES_SHOWN: usize = 12;

/// `g -> i -> h -> j -> g`, or for a long cycle its first and last names around `…` with
/// the number of groups on it (a cycle through 40,000 groups listed all 80,000 names).
fn cycle_names(names: &[&str]) -> String {
    if names.len() <= CYCLE_NAMES_SHOWN {
        return names.join(" -> ");
    }
    let half = CYCLE_NAMES_SHOWN / 2;
    format!(
        "{} -> … -> {} ({} groups)",
        names[..half].join(" -> "),
        names[names.len() - half..].join(" -> "),
        names.len() / 2
    )
}

/// Which objects are reachable from the root (tolerates cycles and dangling names).
pub fn reachable_objects(m: &Merged<'_>, r: &Resolved) -> Vec<bool> {
    let mut objects = vec![false; m.objects.len()];
    let mut groups = vec![false; m.groups.len()];
    let mut todo: Vec<usize> = r.root.into_iter().collect();
    while let Some(g) = todo.pop() {
        if std::mem::replace(&mut groups[g], true) {
            continue;
        }
        for &inst in &r.group_members[g] {
            match r.instance_of[inst] {
                Some(Target::Object(o)) => objects[o] = true,
                Some(Target::Group(child)) => todo.push(child),
                None => {}
            }
        }
    }
    objects
}

/// Expands the acyclic graph from the root group into leaves. `locals` are the instance
/// transforms; the caller has checked they are all valid. `offsets[o]` is the object-space
/// centre subtracted from object `o`'s vertices (see [`super::rebase`]), applied first.
pub fn flatten(
    src: &mut Sources,
    m: &Merged<'_>,
    r: &Resolved,
    locals: &[DAffine3],
    offsets: &[DVec3],
) -> Vec<Leaf> {
    let Some(root) = r.root else {
        return Vec::new();
    };
    struct Frame {
        group: usize,
        next: usize,
        world: DAffine3,
        /// Length of this group's path in the shared `path` (memory stays linear in the
        /// depth: a path per frame was quadratic, 5.7 GB for 40,000 nested groups).
        path_len: usize,
        material: Option<usize>,
        photon: PhotonFlags,
        rays: RayFlags,
    }
    let mut leaves = Vec::new();
    let mut placements = 0usize;
    // `root/instance/…` of the frame on top, then of the instance being placed.
    let mut path = m.groups[root].desc.name.clone();
    let mut stack = vec![Frame {
        group: root,
        next: 0,
        world: DAffine3::IDENTITY,
        path_len: path.len(),
        material: None,
        photon: PhotonFlags::default(),
        rays: RayFlags::default(),
    }];
    while let Some(top) = stack.last_mut() {
        let Some(&inst) = r.group_members[top.group].get(top.next) else {
            stack.pop();
            continue;
        };
        top.next += 1;
        placements += 1;
        if placements > MAX_PLACEMENTS {
            let it = &m.instances[inst];
            src.error(
                it.file,
                &it.at(".of"),
                format!("the scene expands to more than {MAX_PLACEMENTS} placed instances"),
                Some("share fewer groups, or merge meshes".into()),
            );
            return leaves;
        }
        let world = top.world * locals[inst];
        path.truncate(top.path_len);
        path.push('/');
        path.push_str(&m.instances[inst].desc.name);
        let material = r.instance_material[inst].or(top.material);
        let photon = instance_flags(m, inst).or(top.photon);
        let rays = instance_ray_flags(m, inst).or(top.rays);
        match r.instance_of[inst] {
            Some(Target::Object(o)) => {
                let offset = offsets.get(o).copied().unwrap_or(DVec3::ZERO);
                let world = world * DAffine3::from_translation(offset);
                let rounded = Affine3A::from_mat3_translation(
                    world.matrix3.as_mat3(),
                    world.translation.as_vec3(),
                );
                if !rounded.is_finite() || rounded.matrix3.determinant() == 0.0 {
                    let it = &m.instances[inst];
                    let (why, help) = unusable_in_f32(&world, rounded.is_finite());
                    src.error(
                        it.file,
                        &it.at(".transform"),
                        format!("the transform of \"{path}\" composed along its path {why}"),
                        Some(help.into()),
                    );
                    continue;
                }
                leaves.push(Leaf {
                    path: path.clone(),
                    instance: inst,
                    object: o,
                    world_from_object: rounded,
                    world,
                    material: material.or(r.object_material[o]),
                    photon: photon.or(object_flags(m, o)),
                    rays: rays.or(object_ray_flags(m, o)),
                });
            }
            Some(Target::Group(g)) => stack.push(Frame {
                group: g,
                next: 0,
                world,
                path_len: path.len(),
                material,
                photon,
                rays,
            }),
            None => {}
        }
    }
    leaves
}

/// Why a composed transform cannot be rendered in f32 (`finite`: its f32 rounding is finite),
/// and what to do.
fn unusable_in_f32(world: &DAffine3, finite: bool) -> (String, &'static str) {
    let det = world.matrix3.determinant();
    if !finite {
        (
            "does not fit in f32 (a value beyond ±3.4e38)".into(),
            "scale the scene's units down, or the mesh itself instead of its instance",
        )
    } else if det != 0.0 && det.is_finite() {
        (
            format!(
                "scales space so little that its determinant ({det:.3e}) underflows f32, and \
                 the renderer needs its inverse"
            ),
            "scale the mesh itself (or the scene's units) so each instance scales by more \
             than about 1e-12",
        )
    } else {
        (
            "is singular (it flattens space): not invertible".into(),
            "give every axis a non-zero scale",
        )
    }
}

#[cfg(test)]
mod tests {
    use super::cycle_names;

    #[test]
    fn a_short_cycle_is_listed_in_full() {
        assert_eq!(
            cycle_names(&["a", "i", "b", "j", "a"]),
            "a -> i -> b -> j -> a"
        );
    }

    #[test]
    fn a_long_cycle_lists_its_first_and_last_names() {
        let names: Vec<String> = (0..1000)
            .flat_map(|k| [format!("g{k}"), format!("i{k}")])
            .chain(["g0".to_string()])
            .collect();
        let names: Vec<&str> = names.iter().map(String::as_str).collect();
        assert_eq!(
            cycle_names(&names),
            "g0 -> i0 -> g1 -> i1 -> g2 -> i2 -> … -> i997 -> g998 -> i998 -> g999 -> i999 -> g0 (1000 groups)"
        );
    }
}

//! Shortcuts past a convex part's own triangles, for rays that start on it: a ray that leaves
//! the part outward cannot meet it again, and a ray that enters it crosses nothing until it
//! reaches the part's far side. Such a ray is traced from a later origin — past the part's
//! box, or from the far end of its chord through a ball inside the part — so the traversal
//! skips the nodes around its start (a chord of a tessellated ball otherwise tests the boxes
//! of the patches around both its ends); the hit found is then tested again with the
//! original ray, which gives the distance and barycentrics the full query gives.
//!
//! **Parts** are the caller's triangle ranges (an instance's triangles). A part qualifies when
//! it has at least [`MIN_TRIANGLES`] triangles, is wound one way, is *convex*: every vertex
//! lies behind every face's plane (outward = away from the vertices' centroid) within
//! [`CONVEX_TOLERANCE`] of its size, checked for every face against every vertex (relative to
//! the centroid, in a tree of eight-wide boxes whose children behind the plane are skipped
//! whole), and is *isolated*: no other triangle's box meets the part's box grown by
//! [`BOX_MARGIN`]. What the shortcut relies on:
//! - *Leaving* (the ray's direction on the outer side of its face's normal): the part lies
//!   behind the face's plane, the ray moves away from it, so it meets none of the part's
//!   triangles; inside the grown box it meets no other triangle. It is traced from where it
//!   leaves the grown box.
//! - *Entering* (inner side): the ray starts inside the part (its origin is offset to the inner
//!   side of its face) and the ball — centred on the vertices' centroid, the radius its least
//!   distance to a face plane less a margin — lies inside every face's plane, so the segment
//!   from the origin to the ball's far side lies inside the convex part: it crosses no
//!   triangle of the part, and (inside the isolated box) none of any other. It is traced from
//!   the ball's far side.
//!
//! **What comes back** is the full query's answer: the later ray's hit is tested again with
//! the original ray (the watertight test, the kernels' own arithmetic). The two rays
//! run along one line up to the rounding of the later origin, so they can differ only where
//! the line passes within rounding of an edge: a hit whose smallest barycentric is below
//! [`EDGE_GUARD`], a miss of the original ray, or no hit at all is traced again in full
//! ([`Shortcuts::confirm`] answers `None`). Grazing rays (direction within [`GRAZING`] of the face's plane)
//! and rays with a finite `t_max` take no shortcut.

use std::ops::Range;

use glam::{DVec3, Vec3, Vec3A};
use rayon::prelude::*;

use super::triangle::{is_degenerate, ray_is_valid, WoopRay};
use super::{Accel, Hit, Ray};

/// Parts with fewer triangles take no shortcut (what they would save is small).
pub const MIN_TRIANGLES: usize = 64;

/// How far (relative to the part's size) a vertex may lie in front of a face's plane and the
/// part still count as convex: float rounding of exactly planar quads is ~10⁻⁷.
pub const CONVEX_TOLERANCE: f64 = 1e-6;

/// How much (relative to the part's size and its coordinates' magnitude) the part's box is
/// grown, and the inner ball shrunk, beyond the rounding of the later origin.
pub const BOX_MARGIN: f64 = 1e-5;

/// A hit whose smallest barycentric (with the original ray) is below this is traced again.
pub const EDGE_GUARD: f32 = 1e-4;

/// Rays whose direction's cosine with the face normal is below this take no shortcut.
pub const GRAZING: f32 = 1e-3;

/// At most this many parts (the largest) are examined.
const MAX_PARTS: usize = 16;

/// One convex, isolated part.
#[derive(Debug, Clone)]
struct Part {
    /// Its triangles (the caller's indices).
    prims: Range<u32>,
    /// Whether every triangle's geometric normal (`(v₁ − v₀) × (v₂ − v₀)`) points outward
    /// (else every one points inward: a part wound both ways takes no shortcuts).
    ng_outward: bool,
    /// The part's box grown by the margin.
    lo: Vec3,
    hi: Vec3,
    /// The inner ball (radius 0: none).
    centre: Vec3,
    radius: f32,
}

/// The shortcuts of an [`Accel`]'s convex parts ([`Accel::shortcuts`]).
#[derive(Debug, Clone, Default)]
pub struct Shortcuts {
    parts: Vec<Part>,
}

/// What [`Shortcuts::shortcut`] says about a ray.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shortcut {
    /// No shortcut: trace the ray as it is.
    None,
    /// Trace this later ray, then hand its hit to [`Shortcuts::confirm`].
    From(Ray),
}

impl Shortcuts {
    /// The shortcuts of `accel`'s parts `parts` (disjoint ranges of its triangles).
    pub fn build(accel: &Accel, parts: &[Range<u32>]) -> Self {
        let mut candidates: Vec<Range<u32>> = parts
            .iter()
            .filter(|r| r.len() >= MIN_TRIANGLES && r.end as usize <= accel.len())
            .cloned()
            .collect();
        candidates.sort_by_key(|r| (std::cmp::Reverse(r.len()), r.start));
        candidates.truncate(MAX_PARTS);
        let boxes: Vec<Option<(Vec3, Vec3)>> = candidates
            .iter()
            .map(|r| grown_box(accel, r.clone()))
            .collect();
        let isolated = isolated(accel, &candidates, &boxes);
        let mut parts: Vec<Part> = candidates
            .into_par_iter()
            .zip(boxes)
            .zip(isolated)
            .filter_map(|((prims, bounds), isolated)| {
                let (lo, hi) = bounds?;
                isolated
                    .then(|| convex_part(accel, prims, lo, hi))
                    .flatten()
            })
            .collect();
        parts.sort_by_key(|p| p.prims.start);
        Self { parts }
    }

    /// Number of parts that take shortcuts.
    pub fn parts(&self) -> usize {
        self.parts.len()
    }

    /// The shortcut for `ray`, spawned from triangle `from`; `cos_ng` is the cosine between
    /// its direction and that triangle's geometric normal (`(v₁ − v₀) × (v₂ − v₀)`), as the
    /// spawning vertex knows it.
    #[inline]
    pub fn shortcut(&self, ray: &Ray, from: u32, cos_ng: f32) -> Shortcut {
        let i = self.parts.partition_point(|p| p.prims.end <= from);
        let Some(part) = self.parts.get(i).filter(|p| p.prims.contains(&from)) else {
            return Shortcut::None;
        };
        if ray.t_max != f32::INFINITY || !ray.origin.is_finite() || !ray.dir.is_finite() {
            return Shortcut::None;
        }
        let cos = if part.ng_outward { cos_ng } else { -cos_ng };
        let t = if cos > GRAZING {
            Some(leave_box(ray, part.lo, part.hi))
        } else if cos < -GRAZING && part.radius > 0.0 {
            ball_far_side(ray, part.centre, part.radius)
        } else {
            None
        };
        match t {
            Some(t) if t > 0.0 && t.is_finite() => Shortcut::From(Ray {
                origin: ray.origin + ray.dir * t,
                dir: ray.dir,
                t_max: f32::INFINITY,
            }),
            _ => Shortcut::None,
        }
    }

    /// The original `ray`'s closest hit from `found`, the later ray's: `Some` when it is
    /// certain, `None` when the ray is to be traced again in full.
    #[inline]
    pub fn confirm(accel: &Accel, ray: &Ray, found: Option<Hit>) -> Option<Hit> {
        let found = found?;
        // A hit triangle is not degenerate (the hierarchy holds none), so the watertight test
        // proper is `triangle::intersect_triangle`'s answer for it.
        if !ray_is_valid(ray) {
            return None;
        }
        let (t, b1, b2) =
            WoopRay::new(ray.origin, ray.dir).intersect(&accel.triangle(found.prim))?;
        if t >= ray.t_max {
            return None;
        }
        let b0 = 1.0 - b1 - b2;
        (b0.min(b1).min(b2) >= EDGE_GUARD).then_some(Hit {
            t,
            prim: found.prim,
            b1,
            b2,
        })
    }
}

/// Where `ray` leaves the box `lo`–`hi` (its origin inside).
#[inline]
fn leave_box(ray: &Ray, lo: Vec3, hi: Vec3) -> f32 {
    let mut t = f32::INFINITY;
    for a in 0..3 {
        let d = ray.dir[a];
        if d > 0.0 {
            t = t.min((hi[a] - ray.origin[a]) / d);
        } else if d < 0.0 {
            t = t.min((lo[a] - ray.origin[a]) / d);
        }
    }
    t
}

/// The far end of `ray`'s chord through the ball (`centre`, `radius`), when the chord is
/// well inside it (not near the tangent, where the end's rounding grows).
#[inline]
fn ball_far_side(ray: &Ray, centre: Vec3, radius: f32) -> Option<f32> {
    let oc = ray.origin - centre;
    let a = ray.dir.length_squared();
    let b = oc.dot(ray.dir);
    let c = oc.length_squared() - radius * radius;
    let disc = b * b - a * c;
    (disc > 0.01 * a * radius * radius).then(|| (-b + disc.sqrt()) / a)
}

/// The box of the part's non-degenerate triangles, grown by the margin; `None` when it has
/// none or a non-finite vertex.
fn grown_box(accel: &Accel, prims: Range<u32>) -> Option<(Vec3, Vec3)> {
    let (mut lo, mut hi) = (Vec3::INFINITY, Vec3::NEG_INFINITY);
    for prim in prims {
        let tri = accel.triangle(prim);
        if is_degenerate(&tri) {
            continue;
        }
        for v in tri {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return None;
    }
    let scale = f64::from((hi - lo).length().max(lo.abs().max(hi.abs()).max_element()));
    let grow = (BOX_MARGIN * scale) as f32;
    Some((lo - Vec3::splat(grow), hi + Vec3::splat(grow)))
}

/// Whether no triangle outside each part meets the part's grown box (degenerate triangles
/// are never hit and do not count).
fn isolated(accel: &Accel, parts: &[Range<u32>], boxes: &[Option<(Vec3, Vec3)>]) -> Vec<bool> {
    let mut ok: Vec<bool> = boxes.iter().map(Option::is_some).collect();
    for prim in 0..accel.len() as u32 {
        let tri = accel.triangle(prim);
        if is_degenerate(&tri) {
            continue;
        }
        let lo = tri[0].min(tri[1]).min(tri[2]);
        let hi = tri[0].max(tri[1]).max(tri[2]);
        for ((part, bounds), ok) in parts.iter().zip(boxes).zip(&mut ok) {
            if let (true, Some((blo, bhi))) = (*ok, bounds) {
                if !part.contains(&prim) && lo.cmple(*bhi).all() && hi.cmpge(*blo).all() {
                    *ok = false;
                }
            }
        }
    }
    ok
}

/// The part `prims` with its winding and inner ball, when it is convex and wound one way.
fn convex_part(accel: &Accel, prims: Range<u32>, lo: Vec3, hi: Vec3) -> Option<Part> {
    // The triangles that can be hit.
    let tris: Vec<[DVec3; 3]> = prims
        .clone()
        .map(|p| accel.triangle(p))
        .filter(|t| !is_degenerate(t))
        .map(|t| t.map(|v| v.as_dvec3()))
        .collect();
    let vertices = Vertices::new(tris.iter().flatten().copied());
    let centroid = vertices.centroid;
    let size = (hi - lo).as_dvec3().length();
    let tolerance = CONVEX_TOLERANCE * size;
    // Each face's outward plane (unit normal, offset from the centroid), pointing away from
    // the centroid; a face whose plane passes near the centroid makes the part no solid.
    let mut outward = [0usize; 2];
    let planes: Vec<(DVec3, f64)> = tris
        .iter()
        .map(|t| {
            let n = (t[1] - t[0]).cross(t[2] - t[0]).normalize();
            let out = n.dot(t[0] - centroid) >= 0.0;
            outward[usize::from(out)] += 1;
            let n = if out { n } else { -n };
            (n, n.dot(t[0] - centroid))
        })
        .collect();
    if outward[0] != 0 && outward[1] != 0 {
        return None;
    }
    let solid = planes
        .iter()
        .all(|&(n, h)| n.is_finite() && h > 1e-3 * size);
    if !solid
        || !planes
            .par_iter()
            .all(|&(n, h)| vertices.behind(n.as_vec3a(), (h + tolerance) as f32))
    {
        return None;
    }
    let least = planes.iter().map(|&(_, h)| h).fold(f64::INFINITY, f64::min);
    let scale = size.max(f64::from(lo.abs().max(hi.abs()).max_element()));
    let radius = least - 2.0 * tolerance - BOX_MARGIN * scale;
    Some(Part {
        prims,
        ng_outward: outward[1] != 0,
        lo,
        hi,
        centre: centroid.as_vec3(),
        radius: if radius > 0.0 { radius as f32 } else { 0.0 },
    })
}

/// A part's vertices relative to their centroid (`f32`: the values are of the part's size,
/// so their rounding is ~10⁻⁷ of it, well inside [`CONVEX_TOLERANCE`]) in a tree of eight-wide
/// nodes, for "is every vertex behind this plane?": a node holds the boxes of its eight
/// children (structure of arrays: one plane's support for all eight in a few lane
/// operations), and the lowest level's children are the points themselves (boxes of no
/// extent). Missing children are points at the centroid, behind every face of a solid part.
struct Vertices {
    /// Each level's nodes, the points' level first; the last level has one node.
    levels: Vec<Vec<Node8>>,
    centroid: DVec3,
}

/// Eight boxes: `lo[axis][child]`, `hi[axis][child]`.
#[derive(Clone, Copy)]
struct Node8 {
    lo: [[f32; 8]; 3],
    hi: [[f32; 8]; 3],
}

impl Node8 {
    const EMPTY: Node8 = Node8 {
        lo: [[0.0; 8]; 3],
        hi: [[0.0; 8]; 3],
    };

    /// The children whose box reaches in front of the plane `n·p = h` (bit `k`: child `k`).
    #[inline]
    fn in_front(&self, n: [f32; 3], h: f32) -> u32 {
        let mut most = [0.0f32; 8];
        for ((&n, lo), hi) in n.iter().zip(&self.lo).zip(&self.hi) {
            for ((m, &l), &h) in most.iter_mut().zip(lo).zip(hi) {
                *m += (n * l).max(n * h);
            }
        }
        most.iter()
            .enumerate()
            .fold(0, |m, (k, &most)| m | (u32::from(most > h) << k))
    }

    /// The box of all eight children.
    fn bounds(&self) -> ([f32; 3], [f32; 3]) {
        let lo = self
            .lo
            .map(|l| l.iter().copied().fold(f32::INFINITY, f32::min));
        let hi = self
            .hi
            .map(|h| h.iter().copied().fold(f32::NEG_INFINITY, f32::max));
        (lo, hi)
    }
}

impl Vertices {
    fn new(points: impl Iterator<Item = DVec3>) -> Self {
        // Spatial order (a Morton code), equal points next to each other for the dedup.
        let mut keyed: Vec<(u32, [u32; 3])> = points
            .map(|p| (0, p.as_vec3().to_array().map(f32::to_bits)))
            .collect();
        let point = |k: &(u32, [u32; 3])| Vec3::from_array(k.1.map(f32::from_bits)).as_dvec3();
        let (lo, hi) = keyed
            .iter()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), k| {
                (l.min(point(k)), h.max(point(k)))
            });
        let extent = (hi - lo).max(DVec3::splat(f64::MIN_POSITIVE));
        for k in &mut keyed {
            let q = ((point(k) - lo) / extent * 1023.0).as_uvec3();
            k.0 = morton(q.x) | morton(q.y) << 1 | morton(q.z) << 2;
        }
        keyed.sort_unstable();
        keyed.dedup();
        let centroid = keyed.iter().map(point).sum::<DVec3>() / keyed.len().max(1) as f64;
        let boxes: Vec<([f32; 3], [f32; 3])> = keyed
            .iter()
            .map(|k| {
                let p = (point(k) - centroid).as_vec3().to_array();
                (p, p)
            })
            .collect();
        let mut levels = vec![group(&boxes)];
        while levels.last().is_some_and(|l| l.len() > 1) {
            let boxes: Vec<_> = levels
                .last()
                .map_or(Vec::new(), |l| l.iter().map(Node8::bounds).collect());
            levels.push(group(&boxes));
        }
        Self { levels, centroid }
    }

    /// Whether every point `p` has `n·p ≤ h` (both relative to the centroid).
    fn behind(&self, n: Vec3A, h: f32) -> bool {
        let top = self.levels.len() - 1;
        (0..self.levels[top].len()).all(|i| self.behind_in(top, i, n.to_array(), h))
    }

    /// [`Self::behind`] for node `i` of level `level` (0: the points' nodes).
    fn behind_in(&self, level: usize, i: usize, n: [f32; 3], h: f32) -> bool {
        let mut front = self.levels[level][i].in_front(n, h);
        if level == 0 {
            return front == 0;
        }
        while front != 0 {
            let k = front.trailing_zeros() as usize;
            front &= front - 1;
            if !self.behind_in(level - 1, i * 8 + k, n, h) {
                return false;
            }
        }
        true
    }
}

/// `boxes` in nodes of eight (the last one filled with empty children).
fn group(boxes: &[([f32; 3], [f32; 3])]) -> Vec<Node8> {
    boxes
        .chunks(8)
        .map(|bs| {
            let mut node = Node8::EMPTY;
            for (k, (lo, hi)) in bs.iter().enumerate() {
                for a in 0..3 {
                    node.lo[a][k] = lo[a];
                    node.hi[a][k] = hi[a];
                }
            }
            node
        })
        .collect()
}

/// The bits of a 10-bit `x` spread three apart (a Morton code's one axis).
fn morton(x: u32) -> u32 {
    let mut x = x.min(1023);
    x = (x | x << 16) & 0x0300_00ff;
    x = (x | x << 8) & 0x0300_f00f;
    x = (x | x << 4) & 0x030c_30c3;
    (x | x << 2) & 0x0924_9249
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::accel::spawn_ray;
    use crate::accel::test_random::{signed_uniform, uv_sphere};
    use crate::settings::BvhQuality;

    /// A ball of radius 0.6 at (0, 0, 0.9) (`rings` × `segments` quads) above a floor at
    /// z = 0 and before a wall at y = 2, as `caustics.ron`; the parts are the three objects.
    fn ball_scene(ball: Vec<[Vec3; 3]>) -> (Accel, Vec<Range<u32>>) {
        let floor = vec![
            [
                Vec3::new(-3.0, -3.0, 0.0),
                Vec3::new(3.0, -3.0, 0.0),
                Vec3::new(3.0, 3.0, 0.0),
            ],
            [
                Vec3::new(-3.0, -3.0, 0.0),
                Vec3::new(3.0, 3.0, 0.0),
                Vec3::new(-3.0, 3.0, 0.0),
            ],
        ];
        let wall = vec![
            [
                Vec3::new(-3.0, 2.0, 0.0),
                Vec3::new(3.0, 2.0, 0.0),
                Vec3::new(3.0, 2.0, 3.0),
            ],
            [
                Vec3::new(-3.0, 2.0, 0.0),
                Vec3::new(3.0, 2.0, 3.0),
                Vec3::new(-3.0, 2.0, 3.0),
            ],
        ];
        let n = ball.len() as u32;
        let parts = vec![0..n, n..n + 2, n + 2..n + 4];
        let tris = [ball, floor, wall].concat();
        (Accel::build(tris, BvhQuality::Medium), parts)
    }

    fn ball() -> Vec<[Vec3; 3]> {
        uv_sphere(Vec3::new(0.0, 0.0, 0.9), 0.6, 24, 48)
    }

    /// The query as the photon batch makes it: through the shortcut, the full query where
    /// the shortcut's answer is not certain. Also says which way it went.
    fn through(accel: &Accel, shortcuts: &Shortcuts, ray: &Ray, from: u32) -> (Option<Hit>, u8) {
        let ng = accel
            .surface_point(&Hit {
                t: 0.0,
                prim: from,
                b1: 0.3,
                b2: 0.3,
            })
            .ng;
        match shortcuts.shortcut(ray, from, ng.dot(ray.dir.normalize())) {
            Shortcut::None => (accel.intersect(ray), 0),
            Shortcut::From(later) => {
                match Shortcuts::confirm(accel, ray, accel.intersect(&later)) {
                    Some(hit) => (Some(hit), 1),
                    None => (accel.intersect(ray), 2),
                }
            }
        }
    }

    /// Rays that leave the ball (reflected outward, refracted out) and rays that cross it
    /// (refracted in, reflected inside), spawned from hits as the photon walk spawns them,
    /// get the full query's hit bit for bit; almost all of them through the shortcut.
    #[test]
    fn shortcut_answers_are_the_full_queries_bit_for_bit() {
        let (accel, parts) = ball_scene(ball());
        let shortcuts = Shortcuts::build(&accel, &parts);
        assert_eq!(
            shortcuts.parts(),
            1,
            "the ball only (the floor and wall are flat)"
        );
        let mut rnd = signed_uniform(0x5eed_ba11);
        let mut ways = [0usize; 4];
        let (mut leaving, mut crossing) = (0, 0);
        for _ in 0..6000 {
            // From a random point above, at a random point of the ball's upper half.
            let target = Vec3::new(0.0, 0.0, 0.9)
                + Vec3::new(rnd(), rnd(), rnd().abs()).normalize_or_zero() * 0.55;
            let origin = Vec3::new(rnd() * 2.0, rnd() * 2.0, 3.0 + rnd());
            let first = Ray {
                origin,
                dir: target - origin,
                t_max: f32::INFINITY,
            };
            let Some(mut hit) = accel.intersect(&first) else {
                continue;
            };
            // Follow the photon through the ball: each step a random direction on either
            // side of the face, as reflection and refraction give.
            for step in 0..4 {
                let sp = accel.surface_point(&hit);
                let outward = (sp.p - Vec3::new(0.0, 0.0, 0.9)).normalize_or_zero();
                let dir = Vec3::new(rnd(), rnd(), rnd()) * 0.7 + outward;
                let dir = if step % 2 == 0 { -dir } else { dir };
                let ray = spawn_ray(&sp, dir);
                let full = accel.intersect(&ray);
                let (got, way) = through(&accel, &shortcuts, &ray, hit.prim);
                assert_eq!(got, full, "ray {ray:?} from {}", hit.prim);
                if hit.prim < parts[0].end {
                    // Misses are traced again in full (below).
                    ways[if way == 2 && full.is_none() {
                        3
                    } else {
                        way as usize
                    }] += 1;
                    if ray.dir.dot(outward) > 0.0 {
                        leaving += 1;
                    } else {
                        crossing += 1;
                    }
                }
                let Some(next) = full else { break };
                hit = next;
            }
        }
        println!(
            "ways (none, shortcut, retraced hit, retraced miss) {ways:?}; \
             leaving {leaving}, crossing {crossing}"
        );
        assert!(leaving > 3000 && crossing > 3000, "{leaving} {crossing}");
        // Grazing rays and chords near the tangent take none; hits near an edge are traced
        // again, and so are the rays that leave the scene.
        let rays = leaving + crossing;
        assert!(ways[0] < rays / 100, "{ways:?}");
        assert!(ways[2] < rays / 50, "{ways:?}");
    }

    /// A part that is not convex (a dent of a tenth of the radius), one that another
    /// object's box meets (the ball resting on the floor), a small one, and an open flat one
    /// take no shortcut.
    #[test]
    fn only_convex_isolated_parts_take_shortcuts() {
        let convex = |tris: Vec<[Vec3; 3]>| {
            let (accel, parts) = ball_scene(tris);
            Shortcuts::build(&accel, &parts).parts()
        };
        assert_eq!(convex(ball()), 1);
        let top = Vec3::new(0.0, 0.0, 1.5);
        let dented: Vec<[Vec3; 3]> = ball()
            .into_iter()
            .map(|t| {
                t.map(|v| {
                    if v == top {
                        Vec3::new(0.0, 0.0, 1.44)
                    } else {
                        v
                    }
                })
            })
            .collect();
        assert_ne!(dented, ball(), "the dent moved the pole");
        assert_eq!(convex(dented), 0);
        let resting: Vec<[Vec3; 3]> = ball()
            .into_iter()
            .map(|t| t.map(|v| v - Vec3::new(0.0, 0.0, 0.3)))
            .collect();
        assert_eq!(convex(resting), 0);
        assert_eq!(convex(uv_sphere(Vec3::new(0.0, 0.0, 0.9), 0.6, 4, 6)), 0);
        let sheet: Vec<[Vec3; 3]> = (0..40)
            .map(|i| {
                let x = i as f32 * 0.01;
                [
                    Vec3::new(x, 0.0, 1.0),
                    Vec3::new(x + 0.01, 0.0, 1.0),
                    Vec3::new(x, 0.3, 1.0),
                ]
            })
            .chain((0..40).map(|i| {
                let x = i as f32 * 0.01;
                [
                    Vec3::new(x + 0.01, 0.0, 1.0),
                    Vec3::new(x + 0.01, 0.3, 1.0),
                    Vec3::new(x, 0.3, 1.0),
                ]
            }))
            .collect();
        assert_eq!(convex(sheet), 0);
    }
}

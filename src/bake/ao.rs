//! Ambient occlusion and the inside-geometry probe, each from its own rays: AO from
//! cosine-weighted rays about the shading normal (the directions in SIMD lanes:
//! `hemisphere_lanes.rs`), the probe from rays uniform in solid angle, both from a robustly
//! offset origin and generated as one stream per texel. The probe traces closest hits only
//! until its verdict is certain; occlusion is answered by any-hit queries, a texel's rays
//! traced together in common-origin packets (or one query per ray, or the batch kernel:
//! `STAGELIGHT_RAY_STREAMS=off`/`on`).

use glam::{Vec2, Vec3};

use crate::accel::{offset_ray_origin, Ray, SurfacePoint};
use crate::bake::hemisphere_lanes::{DirectionLanes, Frame};
use crate::geometry::SceneGeometry;
use crate::sampling::{first_2d_of_run, sample_uniform_hemisphere};

/// Two tangents completing an orthonormal basis with `n` as its third axis (the shading
/// library's frame: Duff et al. 2017).
pub fn basis(n: Vec3) -> (Vec3, Vec3) {
    let frame = crate::shading::frame::ShadingFrame::from_normal(n);
    (frame.s, frame.t)
}

/// The result of a batch of hemisphere rays from one point.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct HemisphereRays {
    /// Rays used: traced, or drawn below the geometric surface (occluded without a query).
    /// A point found inside geometry stops at the ray that decided it.
    pub rays: u32,
    /// Rays that escaped (no hit within the distance).
    pub open: u32,
    /// Sum of the escaped directions (for bent normals).
    pub open_dir_sum: Vec3,
    /// The inside-geometry verdict (of a probe): more than the fraction of the point's rays
    /// first meet the back of a one-sided surface.
    pub inside: bool,
}

/// What a batch of hemisphere rays is traced for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum HemisphereQuery {
    /// Ambient occlusion only: one occlusion query per ray, up to the distance.
    Occlusion,
    /// The inside-geometry probe: rays uniform in solid angle about the normal (not cosine
    /// weighted: grazing directions count as much as steep ones, so a one-sided surface
    /// overhead whose sides are open leaves them open), and a point is inside when more than
    /// `inside_fraction` of them first meet the back of a one-sided surface. Tracing stops
    /// once the verdict is certain; `open` is not computed. Its rays are never AO rays: an
    /// occlusion estimate from the rays that decided a point is outside would be biased
    /// (those points are the ones whose rays met fewer back faces).
    Probe {
        /// Fraction of back-face first hits above which a point is inside.
        inside_fraction: f32,
    },
}

impl HemisphereQuery {
    fn inside_fraction(self) -> Option<f32> {
        match self {
            Self::Occlusion => None,
            Self::Probe { inside_fraction } => Some(inside_fraction),
        }
    }
}

/// How a texel's occlusion rays are traced. All give the same answers, bit for bit.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Kernel {
    /// Common-origin packets ([`crate::accel::Accel::occluded_packet`]), the default: a
    /// texel's rays leave from its few sample positions, so the packet computes each node's
    /// planes minus the origins once and runs the traversal loop once for all of them
    /// (issue 17, session 11).
    Packets,
    /// One query per ray (`STAGELIGHT_RAY_STREAMS=off`).
    PerRay,
    /// The interleaved batch kernel (`STAGELIGHT_RAY_STREAMS=on`): measured slower here, the
    /// rays are coherent and their nodes cache-resident (sessions 7 and 9).
    Batch,
}

/// The kernel chosen by `STAGELIGHT_RAY_STREAMS` at the first bake (for A/B runs).
fn kernel() -> Kernel {
    static CHOICE: std::sync::OnceLock<Kernel> = std::sync::OnceLock::new();
    *CHOICE.get_or_init(
        || match std::env::var("STAGELIGHT_RAY_STREAMS").as_deref() {
            Ok("on") => Kernel::Batch,
            Ok("off") => Kernel::PerRay,
            _ => Kernel::Packets,
        },
    )
}

/// One sample position's share of a batch of hemisphere rays (see [`trace_hemispheres`]).
#[derive(Debug, Clone, Copy)]
pub struct HemisphereJob<'a> {
    /// The point the rays leave from.
    pub surface: &'a SurfacePoint,
    /// The shading normal, facing the side being baked.
    pub normal: Vec3,
    /// The geometric normal, on the same side.
    pub ng_facing: Vec3,
    /// Sample index of the first ray (`Sampler::new(seed, first + k)` draws ray `k`).
    pub first: u32,
    /// Rays to trace.
    pub count: u32,
}

/// Traces `count` rays about `normal` (which faces the side being baked) from `surface`,
/// each drawn from `Sampler::new(seed, first + k)`: [`trace_hemispheres`] for one point.
#[allow(clippy::too_many_arguments)] // one batch of rays, fully described
pub fn trace_hemisphere(
    geometry: &SceneGeometry,
    surface: &SurfacePoint,
    normal: Vec3,
    ng_facing: Vec3,
    max_distance: f32,
    seed: u32,
    first: u32,
    count: u32,
    query: HemisphereQuery,
) -> HemisphereRays {
    let job = HemisphereJob {
        surface,
        normal,
        ng_facing,
        first,
        count,
    };
    trace_hemispheres(geometry, &[job], max_distance, seed, query)[0]
}

/// The outcome of one drawn ray.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Outcome {
    /// Below the geometric surface: occluded, not traced.
    Below,
    /// Not traced (the point's verdict made it unnecessary).
    Skipped,
    /// Waiting for its occlusion query.
    Pending,
    /// Traced: whether it escaped within the distance.
    Traced { open: bool },
}

/// The hemisphere rays of several points (the sample positions of one texel), generated
/// first and then traced. Per point: `count` rays about `normal` (cosine-weighted for
/// [`HemisphereQuery::Occlusion`], uniform in solid angle for [`HemisphereQuery::Probe`]),
/// ray `k` drawn from `Sampler::new(seed, first + k)`. Directions below the geometric surface
/// (possible with interpolated normals) count as occluded (for the probe: as not meeting a
/// back face) and are not traced. Hits farther than `max_distance` do not occlude.
///
/// Occlusion: every ray is an occlusion (any-hit) query up to `max_distance`, all of them
/// traced in common-origin packets ([`crate::accel::Accel::occluded_packet`]; one query per
/// ray with `STAGELIGHT_RAY_STREAMS=off`, the batch kernel with `on`), each point's sums
/// added in ray order.
///
/// The probe ([`HemisphereQuery::Probe`]): a point's rays are traced in order as closest-hit
/// queries to infinity, each telling whether its first hit is the back of a one-sided
/// surface, only until the inside verdict is certain whatever the remaining rays would show:
/// a point outside is certain once so many rays have not met a back face that the rest
/// cannot reach the fraction (after about a quarter of them), a point inside once more than
/// the fraction have.
pub fn trace_hemispheres(
    geometry: &SceneGeometry,
    jobs: &[HemisphereJob<'_>],
    max_distance: f32,
    seed: u32,
    query: HemisphereQuery,
) -> Vec<HemisphereRays> {
    trace_with(geometry, jobs, max_distance, seed, query, kernel())
}

/// [`trace_hemispheres`] with the given kernel.
fn trace_with(
    geometry: &SceneGeometry,
    jobs: &[HemisphereJob<'_>],
    max_distance: f32,
    seed: u32,
    query: HemisphereQuery,
    kernel: Kernel,
) -> Vec<HemisphereRays> {
    thread_local! {
        static SCRATCH: std::cell::RefCell<Scratch> = std::cell::RefCell::default();
    }
    SCRATCH.with(|cell| match cell.try_borrow_mut() {
        Ok(mut scratch) => {
            let scratch = &mut *scratch;
            trace_in(geometry, jobs, max_distance, seed, query, kernel, scratch)
        }
        Err(_) => {
            let scratch = &mut Scratch::default();
            trace_in(geometry, jobs, max_distance, seed, query, kernel, scratch)
        }
    })
}

/// A thread's working vectors, kept between calls (a bake makes one call per texel).
#[derive(Default)]
struct Scratch {
    /// Each drawn ray (traced ones with their direction), point by point.
    rays: Vec<Option<Ray>>,
    outcomes: Vec<Outcome>,
    /// Each point's rays in `rays`.
    spans: Vec<std::ops::Range<usize>>,
    /// One point's sample points and directions.
    lanes: DirectionLanes,
    queries: Queries,
}

/// The probe's and the occlusion queries' working vectors.
#[derive(Default)]
struct Queries {
    states: Vec<ProbeState>,
    /// The closest hit of each ray, once traced.
    hits: Vec<Option<Option<crate::accel::Hit>>>,
    batch: Vec<Ray>,
    index: Vec<usize>,
    found: Vec<Option<crate::accel::Hit>>,
    occluded: Vec<bool>,
    /// Each ray's occlusion (by index into the rays), once queried.
    blocked: Vec<bool>,
}

/// [`trace_with`] with its working vectors.
fn trace_in(
    geometry: &SceneGeometry,
    jobs: &[HemisphereJob<'_>],
    max_distance: f32,
    seed: u32,
    query: HemisphereQuery,
    kernel: Kernel,
    scratch: &mut Scratch,
) -> Vec<HemisphereRays> {
    let mut out = vec![HemisphereRays::default(); jobs.len()];
    let Scratch {
        rays,
        outcomes,
        spans,
        lanes,
        queries,
    } = scratch;
    rays.clear();
    outcomes.clear();
    spans.clear();
    for job in jobs {
        let (t, b) = basis(job.normal);
        // `offset_ray_origin` depends on the direction only through the side of the surface
        // it leaves on: both origins once per point, the same bits as per ray.
        let n = job.surface.ng;
        let above = offset_ray_origin(job.surface.p, job.surface.p_err, n, n);
        let below = offset_ray_origin(job.surface.p, job.surface.p_err, n, -n);
        let begin = outcomes.len();
        // The sample points first, then their directions in SIMD lanes (the same bits as
        // `t·x + b·y + n·z` of `sample_cosine_hemisphere` one by one).
        lanes.clear();
        first_2d_of_run(seed, job.first, job.count, |u| lanes.push(u));
        let frame = Frame {
            t,
            b,
            n: job.normal,
        };
        let uniform = matches!(query, HemisphereQuery::Probe { .. });
        if !uniform {
            lanes.directions(frame);
        }
        for k in 0..job.count as usize {
            let dir = if uniform {
                let local = sample_uniform_hemisphere(Vec2::new(lanes.u[0][k], lanes.u[1][k]));
                frame.t * local.x + frame.b * local.y + frame.n * local.z
            } else {
                lanes.direction(k)
            };
            if dir.dot(job.ng_facing) <= 0.0 {
                outcomes.push(Outcome::Below);
                rays.push(None);
                continue;
            }
            let origin = if dir.dot(n) < 0.0 { below } else { above };
            outcomes.push(Outcome::Pending);
            rays.push(Some(Ray {
                origin,
                dir,
                t_max: max_distance,
            }));
        }
        spans.push(begin..outcomes.len());
    }
    if let Some(fraction) = query.inside_fraction() {
        let probe_query = Probe {
            max_distance,
            fraction,
            kernel,
        };
        probe(
            geometry,
            rays,
            outcomes,
            spans,
            probe_query,
            queries,
            &mut out,
        );
    }
    if query == HemisphereQuery::Occlusion {
        occlusion(geometry, rays, outcomes, kernel, queries);
        let blocked = &queries.blocked;
        for (outcome, &blocked) in outcomes.iter_mut().zip(blocked.iter()) {
            if *outcome == Outcome::Pending {
                *outcome = Outcome::Traced { open: !blocked };
            }
        }
    }
    for (p, span) in spans.iter().enumerate() {
        let out = &mut out[p];
        for (ray, outcome) in rays[span.clone()].iter().zip(&outcomes[span.clone()]) {
            match outcome {
                Outcome::Below => out.rays += 1,
                Outcome::Skipped | Outcome::Pending => {}
                Outcome::Traced { open } => {
                    out.rays += 1;
                    if *open {
                        out.open += 1;
                        // A traced ray has a direction.
                        out.open_dir_sum += ray.map_or(Vec3::ZERO, |r| r.dir);
                    }
                }
            }
        }
    }
    out
}

/// What the inside-geometry probe is asked.
#[derive(Debug, Clone, Copy)]
struct Probe {
    /// Hits at or beyond this do not occlude.
    max_distance: f32,
    /// Fraction of back-face first hits above which a point is inside.
    fraction: f32,
    kernel: Kernel,
}

/// One point's probe in progress: its rays are consumed in order, as the closest hits come.
#[derive(Debug, Clone, Copy, Default)]
struct ProbeState {
    /// The next ray of the point's span to consume.
    next: usize,
    /// Traced rays whose first hit is the back of a one-sided surface.
    backface: u32,
    /// Rays known not to meet a back face first (below the surface, or traced and not).
    other: u32,
    verdict: Option<bool>,
}

impl ProbeState {
    /// Consumes the point's rays in order while their closest hits are in `hits` (`None`:
    /// not traced yet), exactly as tracing them one by one would, until the verdict is
    /// certain whatever the remaining rays show, or a hit is missing.
    fn advance(
        &mut self,
        geometry: &SceneGeometry,
        rays: &[Option<Ray>],
        hits: &[Option<Option<crate::accel::Hit>>],
        outcomes: &mut [Outcome],
        probe: Probe,
    ) {
        let count = rays.len() as u32;
        let inside = |backface: u32| backface as f32 > probe.fraction * count as f32;
        while self.next < rays.len() {
            if !inside(count - self.other) {
                // Outside whatever the remaining rays show.
                self.verdict = Some(false);
                return;
            }
            let k = self.next;
            let Some(ray) = rays[k] else {
                self.next += 1;
                continue;
            };
            let Some(hit) = hits[k] else { return };
            let back = hit.is_some_and(|hit| {
                let tri = geometry.accel.triangle(hit.prim);
                let ng = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
                ng.dot(ray.dir) > 0.0 && !geometry.material_of(hit.prim).two_sided
            });
            if back {
                self.backface += 1;
            } else {
                self.other += 1;
            }
            outcomes[k] = Outcome::Traced {
                open: hit.is_none_or(|h| h.t >= probe.max_distance),
            };
            self.next += 1;
            if inside(self.backface) {
                self.verdict = Some(true);
                return;
            }
        }
        self.verdict = Some(inside(self.backface));
    }

    /// How many more traced rays the verdict needs at least: as many as it takes for the
    /// rest to fall short of the fraction if none meets a back face, or to exceed it if
    /// all do. Tracing that many next rays at once traces none that one-by-one tracing
    /// would not.
    fn lookahead(&self, count: u32, fraction: f32) -> usize {
        let inside = |backface: u32| backface as f32 > fraction * count as f32;
        let to_outside = (1..=count)
            .find(|k| !inside(count.saturating_sub(self.other + k)))
            .unwrap_or(count);
        let to_inside = (1..=count)
            .find(|k| inside(self.backface + k))
            .unwrap_or(count);
        to_outside.min(to_inside).max(1) as usize
    }
}

/// The inside-geometry verdict of every point (`spans` into `rays`): each point's rays are
/// consumed in order as closest-hit queries to infinity until its verdict is certain; the
/// hits come in rounds, each the fewest next rays of every undecided point that its verdict
/// needs ([`ProbeState::lookahead`]), traced together (common-origin packets by default).
/// Traced rays get their occlusion (a first hit before `max_distance`); once a point's
/// verdict is certain its other rays are skipped. The same verdicts and outcomes result as
/// tracing each point's rays one by one.
fn probe(
    geometry: &SceneGeometry,
    rays: &[Option<Ray>],
    outcomes: &mut [Outcome],
    spans: &[std::ops::Range<usize>],
    probe: Probe,
    queries: &mut Queries,
    out: &mut [HemisphereRays],
) {
    let Queries {
        states,
        hits,
        batch,
        index,
        found,
        ..
    } = queries;
    states.clear();
    states.resize(spans.len(), ProbeState::default());
    for (state, span) in states.iter_mut().zip(spans) {
        state.other = outcomes[span.clone()]
            .iter()
            .filter(|o| **o == Outcome::Below)
            .count() as u32;
    }
    hits.clear();
    hits.resize(rays.len(), None);
    loop {
        for (state, span) in states.iter_mut().zip(spans) {
            if state.verdict.is_none() {
                state.advance(
                    geometry,
                    &rays[span.clone()],
                    &hits[span.clone()],
                    &mut outcomes[span.clone()],
                    probe,
                );
            }
        }
        batch.clear();
        index.clear();
        for (state, span) in states.iter().zip(spans) {
            if state.verdict.is_some() {
                continue;
            }
            let want = state.lookahead(span.len() as u32, probe.fraction);
            let next = span.start + state.next;
            for k in (next..span.end).filter(|&k| rays[k].is_some()).take(want) {
                if let (Some(ray), None) = (rays[k], hits[k]) {
                    batch.push(Ray {
                        t_max: f32::INFINITY,
                        ..ray
                    });
                    index.push(k);
                }
            }
        }
        if batch.is_empty() {
            break;
        }
        found.clear();
        found.resize(batch.len(), None);
        closest(geometry, batch, found, probe.kernel);
        for (&k, &hit) in index.iter().zip(found.iter()) {
            hits[k] = Some(hit);
        }
    }
    for ((state, span), out) in states.iter().zip(spans).zip(out) {
        for o in outcomes[span.clone()]
            .iter_mut()
            .filter(|o| **o == Outcome::Pending)
        {
            *o = Outcome::Skipped;
        }
        out.inside = state.verdict.unwrap_or(false);
    }
}

/// Closest-hit batches smaller than this are traced one query per ray even with
/// [`Kernel::Packets`]: a packet's fixed cost (its 64-ray state) outweighs the sharing for
/// the few rays of a probe round (issue 17, session 14).
const SMALL_CLOSEST_BATCH: usize = 32;

/// Closest hits of `rays` with the chosen kernel (see [`Kernel`]).
fn closest(
    geometry: &SceneGeometry,
    rays: &[Ray],
    out: &mut [Option<crate::accel::Hit>],
    kernel: Kernel,
) {
    match kernel {
        Kernel::Packets if rays.len() >= SMALL_CLOSEST_BATCH => {
            geometry.accel.intersect_packet(rays, out)
        }
        Kernel::Packets => {
            for (ray, out) in rays.iter().zip(out) {
                *out = geometry.accel.intersect(ray);
            }
        }
        Kernel::Batch => geometry.accel.intersect_batch(rays, out),
        Kernel::PerRay => {
            for (ray, out) in rays.iter().zip(out) {
                *out = geometry.accel.intersect(ray);
            }
        }
    }
}

/// Occlusion queries (up to each ray's `t_max`, the distance) for every pending ray, into
/// `queries.blocked` (by ray; false for the others): in common-origin packets, one query per
/// ray or one batch (see [`Kernel`]).
fn occlusion(
    geometry: &SceneGeometry,
    rays: &[Option<Ray>],
    outcomes: &[Outcome],
    kernel: Kernel,
    queries: &mut Queries,
) {
    let Queries {
        batch,
        index,
        occluded,
        blocked,
        ..
    } = queries;
    blocked.clear();
    blocked.resize(rays.len(), false);
    if kernel == Kernel::PerRay {
        for ((ray, outcome), blocked) in rays.iter().zip(outcomes).zip(blocked.iter_mut()) {
            if let (Some(ray), Outcome::Pending) = (ray, outcome) {
                *blocked = geometry.accel.occluded(ray);
            }
        }
        return;
    }
    batch.clear();
    index.clear();
    for (i, (ray, outcome)) in rays.iter().zip(outcomes.iter()).enumerate() {
        if let (Some(ray), Outcome::Pending) = (ray, outcome) {
            batch.push(*ray);
            index.push(i);
        }
    }
    occluded.clear();
    occluded.resize(batch.len(), false);
    if kernel == Kernel::Batch {
        geometry.accel.occluded_batch(batch, occluded);
    } else {
        geometry.accel.occluded_packet(batch, occluded);
    }
    for (&i, &hit) in index.iter().zip(occluded.iter()) {
        blocked[i] = hit;
    }
}
#[cfg(test)]
mod tests {
    use super::*;
    use crate::sampling::{sample_cosine_hemisphere, Sampler};
    use crate::shading::integrator::fixture::{self, Object};

    /// What tracing every ray to its first hit gives (the bake before the probe stopped
    /// early): rays, escaped rays, their direction sum, back-face first hits; the rays
    /// cosine-weighted, or uniform in solid angle (`uniform`, the probe's).
    fn reference(
        geometry: &SceneGeometry,
        job: &HemisphereJob<'_>,
        max_distance: f32,
        seed: u32,
        uniform: bool,
    ) -> (u32, u32, Vec3, u32) {
        let (t, b) = basis(job.normal);
        let (mut open, mut sum, mut back) = (0, Vec3::ZERO, 0);
        for k in 0..job.count {
            let u = Sampler::new(seed, job.first + k).next_2d();
            let local = if uniform {
                crate::sampling::sample_uniform_hemisphere(u)
            } else {
                sample_cosine_hemisphere(u)
            };
            let dir = t * local.x + b * local.y + job.normal * local.z;
            if dir.dot(job.ng_facing) <= 0.0 {
                continue;
            }
            let hit = geometry
                .accel
                .intersect(&crate::accel::spawn_ray(job.surface, dir));
            if let Some(h) = hit {
                let tri = geometry.accel.triangle(h.prim);
                let ng = (tri[1] - tri[0]).cross(tri[2] - tri[0]);
                back += u32::from(ng.dot(dir) > 0.0 && !geometry.material_of(h.prim).two_sided);
            }
            if hit.is_none_or(|h| h.t >= max_distance) {
                open += 1;
                sum += dir;
            }
        }
        (job.count, open, sum, back)
    }

    /// A floor (one-sided, facing up), a closed one-sided box sunk into it, a one-sided wall
    /// standing on it with its back to the probe points, and a two-sided roof.
    /// One job of `count` rays per surface point, normals taken in turn from `normals`,
    /// sample indices `stride` apart.
    fn hemisphere_jobs<'a>(
        surfaces: &'a [SurfacePoint],
        normals: &[Vec3],
        stride: u32,
        count: u32,
    ) -> Vec<HemisphereJob<'a>> {
        surfaces
            .iter()
            .zip(normals.iter().cycle())
            .enumerate()
            .map(|(i, (s, &normal))| HemisphereJob {
                surface: s,
                normal,
                ng_facing: s.ng,
                first: stride * i as u32,
                count,
            })
            .collect()
    }

    /// The surface point that a ray from one unit below `p`, going up, meets first.
    fn floor_point(g: &SceneGeometry, p: Vec3) -> SurfacePoint {
        g.accel
            .surface_point(&fixture::hit(g, p - Vec3::Z, Vec3::Z).1)
    }

    fn scene() -> SceneGeometry {
        // Its faces: the fixture's cube is wound so that its normals point out.
        let cube: Vec<[Vec3; 3]> = fixture::inward_cube(0.25)
            .into_iter()
            .map(|t| t.map(|v| v + Vec3::new(0.5, 0.5, 0.2)))
            .collect();
        let wall = fixture::quad(
            Vec3::new(-0.5, -1.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(0.0, 2.0, 0.0),
        );
        let roof = fixture::quad(
            Vec3::new(-1.0, -1.0, 0.6),
            Vec3::new(0.4, 0.0, 0.0),
            Vec3::new(0.0, 0.5, 0.0),
        );
        let mut two_sided = fixture::lambert(0.5);
        two_sided.two_sided = true;
        fixture::geometry(vec![
            Object {
                triangles: fixture::floor(2.0, 0.0),
                material: fixture::lambert(0.5),
            },
            Object {
                triangles: cube,
                material: fixture::lambert(0.5),
            },
            Object {
                triangles: wall,
                material: fixture::lambert(0.5),
            },
            Object {
                triangles: roof,
                material: two_sided,
            },
        ])
    }

    /// The probe stops tracing once its verdict is certain and occlusion uses any-hit
    /// queries, yet every point gets the verdict (of the probe's uniform rays) and the
    /// escaped count and the direction sum (of the AO's cosine rays, bit for bit) of tracing
    /// every ray to its first hit: inside the box, beside the wall's back (about half the
    /// rays meet a back face, so the fraction decides), under the roof and in the open, at
    /// several fractions, distances and ray counts, with a tilted shading normal that sends
    /// some directions below the surface.
    #[test]
    fn early_probe_and_any_hit_occlusion_match_tracing_every_ray() {
        let g = scene();
        let points = [
            Vec3::new(0.5, 0.5, 0.0),
            Vec3::new(0.45, 0.6, 0.0),
            Vec3::new(-0.52, 0.1, 0.0),
            Vec3::new(-0.45, 0.0, 0.0),
            Vec3::new(-0.49, 0.3, 0.0),
            Vec3::new(-0.8, -0.8, 0.0),
            Vec3::new(1.5, -1.5, 0.0),
            Vec3::new(0.8, 0.5, 0.0),
        ];
        // From below: the floor is the first surface up there.
        let floor_hit = |p: Vec3| fixture::hit(&g, p - Vec3::Z, Vec3::Z).1;
        let surfaces: Vec<SurfacePoint> = points
            .iter()
            .map(|&p| g.accel.surface_point(&floor_hit(p)))
            .collect();
        let normals = [Vec3::Z, Vec3::new(0.6, 0.0, 0.8)];
        let (mut insides, mut outsides) = (0, 0);
        for (seed, fraction, max_distance, count) in [
            (1, 0.75, f32::INFINITY, 16),
            (2, 0.5, 0.3, 16),
            (3, 0.25, 2.0, 5),
            (4, 0.75, f32::INFINITY, 8),
            (5, 0.4, 0.05, 1),
            (6, 0.5, f32::INFINITY, 64),
        ] {
            let jobs = hemisphere_jobs(&surfaces, &normals, 3, count);
            let probe = trace_hemispheres(
                &g,
                &jobs,
                max_distance,
                seed,
                HemisphereQuery::Probe {
                    inside_fraction: fraction,
                },
            );
            let occlusion =
                trace_hemispheres(&g, &jobs, max_distance, seed, HemisphereQuery::Occlusion);
            for (p, job) in jobs.iter().enumerate() {
                let (rays, open, sum, _) = reference(&g, job, max_distance, seed, false);
                let (_, _, _, back) = reference(&g, job, max_distance, seed, true);
                let inside = back as f32 > fraction * rays as f32;
                let case = format!("point {p}, seed {seed}");
                assert_eq!(
                    (occlusion[p].rays, occlusion[p].open),
                    (rays, open),
                    "{case}"
                );
                assert_eq!(
                    occlusion[p].open_dir_sum.to_array().map(f32::to_bits),
                    sum.to_array().map(f32::to_bits),
                    "{case}"
                );
                assert_eq!(probe[p].inside, inside, "{case}");
                assert!(!occlusion[p].inside, "{case}");
                assert!(probe[p].rays <= rays, "{case}");
                if inside {
                    insides += 1;
                } else {
                    outsides += 1;
                }
            }
        }
        assert!(
            insides >= 6 && outsides >= 12,
            "{insides} inside, {outsides} outside"
        );
    }

    /// The three kernels (common-origin packets, one query per ray, interleaved batches)
    /// give every point the same rays, verdict, escaped count and direction sum, bit for
    /// bit, for every query: many points in one call (more origins than one packet holds),
    /// inside the closed box, beside the wall's back, under the roof and in the open.
    #[test]
    fn packets_per_ray_and_batch_kernels_agree() {
        let g = scene();
        let surfaces: Vec<SurfacePoint> = (0..24)
            .map(|i| {
                let p = Vec3::new(-0.9 + 0.08 * i as f32, 0.4 + 0.1 * (i % 3) as f32, 0.0);
                g.accel
                    .surface_point(&fixture::hit(&g, p - Vec3::Z, Vec3::Z).1)
            })
            .collect();
        let normals = [
            Vec3::Z,
            Vec3::new(0.6, 0.0, 0.8),
            Vec3::new(0.0, -0.28, 0.96),
        ];
        let bits = |r: &HemisphereRays| {
            (
                r.rays,
                r.open,
                r.open_dir_sum.to_array().map(f32::to_bits),
                r.inside,
            )
        };
        let mut inside = 0;
        for (seed, count, max_distance) in [(7, 16, f32::INFINITY), (8, 64, 0.4), (9, 5, 2.0)] {
            let jobs = hemisphere_jobs(&surfaces, &normals, 5, count);
            for query in [
                HemisphereQuery::Occlusion,
                HemisphereQuery::Probe {
                    inside_fraction: 0.5,
                },
                HemisphereQuery::Probe {
                    inside_fraction: 0.75,
                },
            ] {
                let run = |k| trace_with(&g, &jobs, max_distance, seed, query, k);
                let packets = run(Kernel::Packets);
                let per_ray = run(Kernel::PerRay);
                let batch = run(Kernel::Batch);
                for p in 0..jobs.len() {
                    let case = format!("point {p}, seed {seed}, {query:?}");
                    assert_eq!(bits(&packets[p]), bits(&per_ray[p]), "{case}");
                    assert_eq!(bits(&batch[p]), bits(&per_ray[p]), "{case}");
                    inside += usize::from(per_ray[p].inside);
                }
            }
        }
        assert!(inside >= 4, "{inside} points inside");
    }

    /// Outside in the open the probe decides after a quarter of the rays and inside a closed
    /// box after three quarters: it traces fewer rays than it draws. (The open point is on
    /// the wall's front side, where no ray can meet a back face: the probe's grazing rays
    /// would meet the wall's back from the other side.)
    #[test]
    fn the_probe_stops_when_its_verdict_is_certain() {
        let g = scene();
        let hit = |p: Vec3| floor_point(&g, p);
        let (open, boxed) = (
            hit(Vec3::new(-1.5, 1.5, 0.0)),
            hit(Vec3::new(0.5, 0.5, 0.0)),
        );
        let job = |s| HemisphereJob {
            surface: s,
            normal: Vec3::Z,
            ng_facing: Vec3::Z,
            first: 0,
            count: 16,
        };
        let query = HemisphereQuery::Probe {
            inside_fraction: 0.75,
        };
        let r = trace_hemispheres(&g, &[job(&open), job(&boxed)], f32::INFINITY, 9, query);
        // 16 rays: outside is certain after 4 rays miss back faces, inside once 13 meet
        // them. The boxed point lies on the inward cube's bottom, under the floor: steep
        // rays meet the floor's back, while the probe's uniform rays 1, 4 and 13 graze
        // along the slab into the cube's inward (front) walls, so the 13th back face is the
        // 16th ray's.
        assert_eq!((r[0].inside, r[0].rays), (false, 4));
        assert_eq!((r[1].inside, r[1].rays), (true, 16));
    }

    #[test]
    fn basis_is_orthonormal() {
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::X,
            Vec3::new(0.3, -0.4, 0.866).normalize(),
        ] {
            let (t, b) = basis(n);
            assert!(t.dot(b).abs() < 1e-6 && t.dot(n).abs() < 1e-6 && b.dot(n).abs() < 1e-6);
            assert!((t.length() - 1.0).abs() < 1e-6 && (b.length() - 1.0).abs() < 1e-6);
            assert!((t.cross(b) - n).length() < 1e-5);
        }
    }
}

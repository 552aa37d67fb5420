//! Dicing a patch complex crack-free.
//!
//! 1. **Topology.** Every patch side is keyed by its corner ids in canonical order
//!    (smaller id first); the first patch that lists an edge owns it.
//! 2. **Edge rates.** The owner samples the edge in canonical order (displaced when true
//!    displacement is on) and [`rates`] turns the samples into a segment count. Nothing but
//!    the edge enters, so both neighbours agree.
//! 3. **Shared vertices.** Corners and edge vertices are evaluated once (by their owner) and
//!    displaced once, along the normal averaged over the patches that meet there.
//! 4. **Patches.** Each patch picks interior rates, evaluates its interior grid and stitches it
//!    to the shared boundary vertices with monotone triangle strips ("zippers"). When the
//!    boundary rates equal the interior rates the patch is a plain grid.
//! 5. **Output.** Vertices are emitted per patch (so uv seams survive) with positions copied
//!    bit for bit from the welded vertex; displaced meshes get normals recomputed from the
//!    displaced triangles (area-weighted over the welded vertex).

use std::collections::HashMap;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::displace::Displacer;
use super::rates::{Direction, RateContext};
use super::{GeometryError, Options, PatchSource, SurfaceSample, Tessellation};
use crate::components::{SurfaceDerivatives, TriMesh};

/// Samples per edge for rate decisions (more when displacement may add detail).
const RATE_SAMPLES: usize = 16;
/// Samples per edge for rate decisions on displaced surfaces.
const RATE_SAMPLES_DISPLACED: usize = 64;

/// Reference from a patch side to its edge.
#[derive(Debug, Clone, Copy)]
struct SideRef {
    /// Edge index, or `u32::MAX` for a degenerate side (both corners the same).
    edge: u32,
    /// The side runs from the larger corner id to the smaller one.
    reversed: bool,
}

/// A shared edge.
#[derive(Debug, Clone, Copy)]
struct Edge {
    owner: u32,
    side: u8,
    owner_reversed: bool,
    /// A second patch using the edge, if any (for averaged displacement normals).
    other: Option<(u32, u8, bool)>,
}

/// Local parameters of a point at `t` along `side` (in the side's own direction).
#[inline]
fn side_param(side: u8, t: f64) -> (f64, f64) {
    match side {
        0 => (t, 0.0),
        1 => (1.0, t),
        2 => (t, 1.0),
        _ => (0.0, t),
    }
}

/// Corner slots at the start and end of a side, in the side's direction.
const SIDE_CORNERS: [(usize, usize); 4] = [(0, 1), (1, 2), (3, 2), (0, 3)];
/// Local parameters of the four corner slots.
const CORNER_PARAMS: [(f64, f64); 4] = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];

/// One patch's output: local vertices and triangles.
#[derive(Default)]
struct PatchOut {
    gid: Vec<u32>,
    pos: Vec<DVec3>,
    n: Vec<DVec3>,
    uv: Vec<DVec2>,
    dpdu: Vec<DVec3>,
    dpdv: Vec<DVec3>,
    tris: Vec<[u32; 3]>,
}

impl PatchOut {
    fn push(&mut self, gid: u32, s: &SurfaceSample, pos: DVec3, derivs: bool) -> u32 {
        let i = self.gid.len() as u32;
        self.gid.push(gid);
        self.pos.push(pos);
        self.n.push(s.n);
        self.uv.push(s.uv);
        if derivs {
            self.dpdu.push(s.dpdu);
            self.dpdv.push(s.dpdv);
        }
        i
    }
}

/// Tessellates a patch complex.
pub fn tessellate(src: &dyn PatchSource, opts: &Options) -> Result<Tessellation, GeometryError> {
    let displacer = opts.displacement.map(Displacer::new).transpose()?;
    let displacer = displacer.as_ref();
    let ctx = RateContext::new(opts.approximation, opts.view, src.grid())?;
    let patches = src.patch_count();
    let corner_count = src.corner_count();

    // 1. Topology.
    let mut edges: Vec<Edge> = Vec::new();
    let mut sides: Vec<[SideRef; 4]> = Vec::with_capacity(patches);
    let mut edge_map: HashMap<(u32, u32), u32> = HashMap::new();
    let mut corner_refs: Vec<Vec<(u32, u8)>> = vec![Vec::new(); corner_count];
    for p in 0..patches {
        let c = src.corners(p);
        if c.iter().any(|&id| id as usize >= corner_count) {
            return Err(GeometryError::BadCount {
                message: format!("patch {p} has a corner id beyond {corner_count}"),
            });
        }
        for (slot, &id) in c.iter().enumerate() {
            corner_refs[id as usize].push((p as u32, slot as u8));
        }
        let mut refs = [SideRef {
            edge: u32::MAX,
            reversed: false,
        }; 4];
        for (side, &(s0, s1)) in SIDE_CORNERS.iter().enumerate() {
            let (a, b) = (c[s0], c[s1]);
            if a == b {
                continue;
            }
            let reversed = a > b;
            let key = (a.min(b), a.max(b));
            let e = *edge_map.entry(key).or_insert_with(|| {
                edges.push(Edge {
                    owner: p as u32,
                    side: side as u8,
                    owner_reversed: reversed,
                    other: None,
                });
                edges.len() as u32 - 1
            });
            let edge = &mut edges[e as usize];
            if edge.owner != p as u32 && edge.other.is_none() {
                edge.other = Some((p as u32, side as u8, reversed));
            }
            refs[side] = SideRef { edge: e, reversed };
        }
        sides.push(refs);
    }

    // 2. Edge rates, from the edge alone (owner's samples in canonical order).
    let samples = if displacer.is_some() {
        RATE_SAMPLES_DISPLACED
    } else {
        RATE_SAMPLES
    };
    let edge_rates: Vec<u32> = edges
        .par_iter()
        .map(|e| {
            let dir = if e.side % 2 == 0 {
                Direction::U
            } else {
                Direction::V
            };
            let curve = sample_curve(src, displacer, samples, |t| {
                let t = if e.owner_reversed { 1.0 - t } else { t };
                (e.owner as usize, side_param(e.side, t))
            });
            ctx.rate(&curve.0, &curve.1, dir)
        })
        .collect();
    let side_rate = |r: SideRef| {
        if r.edge == u32::MAX {
            1
        } else {
            edge_rates[r.edge as usize]
        }
    };

    // 3. Interior rates per patch.
    let interior: Vec<(u32, u32)> = (0..patches)
        .into_par_iter()
        .map(|p| {
            let s = &sides[p];
            let (mut mu, mut mv) = (
                side_rate(s[0]).max(side_rate(s[2])),
                side_rate(s[1]).max(side_rate(s[3])),
            );
            if ctx.is_adaptive() {
                let iso_u = sample_curve(src, displacer, samples, |t| (p, (t, 0.5)));
                let iso_v = sample_curve(src, displacer, samples, |t| (p, (0.5, t)));
                mu = mu.max(ctx.rate(&iso_u.0, &iso_u.1, Direction::U));
                mv = mv.max(ctx.rate(&iso_v.0, &iso_v.1, Direction::V));
            } else {
                mu = mu.max(ctx.fixed_rate(Direction::U));
                mv = mv.max(ctx.fixed_rate(Direction::V));
            }
            (mu, mv)
        })
        .collect();

    // Refuse before dicing what would not fit (two triangles per interior cell, plus the
    // stitching, which never adds more than the boundary).
    let triangles = interior.iter().fold(0u64, |t, &(mu, mv)| {
        t.saturating_add(2 * u64::from(mu) * u64::from(mv))
    });
    if triangles > opts.max_triangles {
        return Err(GeometryError::TooManyTriangles {
            triangles,
            limit: opts.max_triangles,
        });
    }

    // 4. Shared vertices: corners, then each edge's interior vertices.
    let mut edge_first = Vec::with_capacity(edges.len());
    let mut shared = corner_count as u32;
    for &r in &edge_rates {
        edge_first.push(shared);
        shared += r - 1;
    }
    let corner_pos: Vec<DVec3> = (0..corner_count)
        .into_par_iter()
        .map(|c| {
            let refs = &corner_refs[c];
            let Some(&(p, slot)) = refs.first() else {
                return DVec3::ZERO;
            };
            let (u, v) = CORNER_PARAMS[slot as usize];
            let s = src.eval(p as usize, u, v);
            match displacer {
                None => s.p,
                Some(d) => {
                    let n = refs
                        .iter()
                        .map(|&(q, k)| {
                            let (u, v) = CORNER_PARAMS[k as usize];
                            src.eval(q as usize, u, v).n
                        })
                        .fold(DVec3::ZERO, |a, b| a + b);
                    d.displace(&s, n.try_normalize().unwrap_or(s.n))
                }
            }
        })
        .collect();
    let edge_pos: Vec<Vec<DVec3>> = edges
        .par_iter()
        .zip(edge_rates.par_iter())
        .map(|(e, &rate)| {
            (1..rate)
                .map(|m| {
                    let tc = m as f64 / rate as f64;
                    let t = if e.owner_reversed { 1.0 - tc } else { tc };
                    let (u, v) = side_param(e.side, t);
                    let s = src.eval(e.owner as usize, u, v);
                    match displacer {
                        None => s.p,
                        Some(d) => {
                            let mut n = s.n;
                            if let Some((q, side, rev)) = e.other {
                                let t = if rev { 1.0 - tc } else { tc };
                                let (u, v) = side_param(side, t);
                                n += src.eval(q as usize, u, v).n;
                            }
                            d.displace(&s, n.try_normalize().unwrap_or(s.n))
                        }
                    }
                })
                .collect()
        })
        .collect();
    let shared_pos = |gid: u32| -> DVec3 {
        if (gid as usize) < corner_count {
            corner_pos[gid as usize]
        } else {
            let e = edge_first.partition_point(|&f| f <= gid) - 1;
            edge_pos[e][(gid - edge_first[e]) as usize]
        }
    };

    // 5. Patches: interior grids and stitching.
    let mut interior_first = Vec::with_capacity(patches);
    let mut next = shared;
    for &(mu, mv) in &interior {
        interior_first.push(next);
        next += interior_vertex_count(mu, mv);
    }
    let outs: Vec<PatchOut> = (0..patches)
        .into_par_iter()
        .map(|p| {
            let corners = src.corners(p);
            let boundary: [Vec<u32>; 4] = std::array::from_fn(|side| {
                let r = sides[p][side];
                let rate = side_rate(r);
                let (s0, s1) = SIDE_CORNERS[side];
                (0..=rate)
                    .map(|k| {
                        if k == 0 {
                            corners[s0]
                        } else if k == rate {
                            corners[s1]
                        } else {
                            let m = if r.reversed { rate - k } else { k };
                            edge_first[r.edge as usize] + m - 1
                        }
                    })
                    .collect()
            });
            dice_patch(
                src,
                p,
                &boundary,
                interior[p],
                interior_first[p],
                &shared_pos,
                displacer,
                opts.derivatives,
            )
        })
        .collect();

    Ok(assemble(
        outs,
        next as usize,
        displacer.is_some(),
        opts.derivatives,
    ))
}

/// Evaluates `samples + 1` points of a curve given by `at(t)` → (patch, (u, v)), displaced
/// along the patch normal when a displacer is given. Returns positions and normals.
fn sample_curve(
    src: &dyn PatchSource,
    displacer: Option<&Displacer>,
    samples: usize,
    at: impl Fn(f64) -> (usize, (f64, f64)),
) -> (Vec<DVec3>, Vec<DVec3>) {
    let mut pts = Vec::with_capacity(samples + 1);
    let mut nrm = Vec::with_capacity(samples + 1);
    for k in 0..=samples {
        let (p, (u, v)) = at(k as f64 / samples as f64);
        let s = src.eval(p, u, v);
        pts.push(match displacer {
            None => s.p,
            Some(d) => d.displace(&s, s.n),
        });
        nrm.push(s.n);
    }
    (pts, nrm)
}

/// Interior vertices of a patch with interior rates (mu, mv).
fn interior_vertex_count(mu: u32, mv: u32) -> u32 {
    (mu.max(2) - 1) * (mv.max(2) - 1)
}

/// Dices one patch. `boundary[side]` lists the global ids along each side in the side's own
/// direction; interior vertices get ids from `first_interior`.
#[allow(clippy::too_many_arguments)] // one call site; a struct would only rename them
fn dice_patch(
    src: &dyn PatchSource,
    p: usize,
    boundary: &[Vec<u32>; 4],
    (mu, mv): (u32, u32),
    first_interior: u32,
    shared_pos: &(dyn Fn(u32) -> DVec3 + Sync),
    displacer: Option<&Displacer>,
    derivs: bool,
) -> PatchOut {
    let mut out = PatchOut::default();
    let rates: [u32; 4] = std::array::from_fn(|k| boundary[k].len() as u32 - 1);
    // Boundary vertices: shared positions, the patch's own uv/normal/derivatives.
    let mut side_local: [Vec<u32>; 4] = Default::default();
    let mut corner_local = [u32::MAX; 4];
    for side in 0..4 {
        let (s0, s1) = SIDE_CORNERS[side];
        let e = rates[side];
        for (k, &gid) in boundary[side].iter().enumerate() {
            let slot = if k == 0 {
                Some(s0)
            } else if k as u32 == e {
                Some(s1)
            } else {
                None
            };
            if let Some(slot) = slot {
                if corner_local[slot] != u32::MAX {
                    side_local[side].push(corner_local[slot]);
                    continue;
                }
            }
            let (u, v) = side_param(side as u8, k as f64 / e as f64);
            let s = src.eval(p, u, v);
            let l = out.push(gid, &s, shared_pos(gid), derivs);
            if let Some(slot) = slot {
                corner_local[slot] = l;
            }
            side_local[side].push(l);
        }
    }
    let plain = rates[0] == mu && rates[2] == mu && rates[1] == mv && rates[3] == mv;
    if mu == 1 && mv == 1 && plain {
        let [c0, c1, c2, c3] = corner_local;
        out.tris.push([c0, c1, c2]);
        out.tris.push([c0, c2, c3]);
        drop_degenerate(&mut out);
        return out;
    }
    let (mu, mv) = if plain {
        (mu, mv)
    } else {
        (mu.max(2), mv.max(2))
    };
    // Interior grid (i, j) for i in 1..mu, j in 1..mv.
    let (iu, iv) = (mu - 1, mv - 1);
    let first_local = out.gid.len() as u32;
    for j in 1..mv {
        let v = j as f64 / mv as f64;
        for i in 1..mu {
            let u = i as f64 / mu as f64;
            let s = src.eval(p, u, v);
            let pos = match displacer {
                None => s.p,
                Some(d) => d.displace(&s, s.n),
            };
            let gid = first_interior + (i - 1) + (j - 1) * iu;
            out.push(gid, &s, pos, derivs);
        }
    }
    let inner = |i: u32, j: u32| first_local + (i - 1) + (j - 1) * iu;
    if plain {
        // Full grid: index (i, j) from boundary or interior.
        let at = |i: u32, j: u32| -> u32 {
            if j == 0 {
                side_local[0][i as usize]
            } else if j == mv {
                side_local[2][i as usize]
            } else if i == 0 {
                side_local[3][j as usize]
            } else if i == mu {
                side_local[1][j as usize]
            } else {
                inner(i, j)
            }
        };
        out.tris.reserve((2 * mu * mv) as usize);
        for j in 0..mv {
            for i in 0..mu {
                let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
                out.tris.push([a, b, c]);
                out.tris.push([a, c, d]);
            }
        }
    } else {
        for j in 1..iv {
            for i in 1..iu {
                let (a, b, c, d) = (
                    inner(i, j),
                    inner(i + 1, j),
                    inner(i + 1, j + 1),
                    inner(i, j + 1),
                );
                out.tris.push([a, b, c]);
                out.tris.push([a, c, d]);
            }
        }
        let rows: [Vec<u32>; 4] = [
            (1..mu).map(|i| inner(i, 1)).collect(),
            (1..mv).map(|j| inner(mu - 1, j)).collect(),
            (1..mu).map(|i| inner(i, mv - 1)).collect(),
            (1..mv).map(|j| inner(1, j)).collect(),
        ];
        for side in 0..4 {
            let m = if side % 2 == 0 { mu } else { mv };
            zipper(&side_local[side], &rows[side], m, side >= 2, &mut out.tris);
        }
    }
    drop_degenerate(&mut out);
    out
}

/// Triangulates the strip between an outer polyline (`outer`, parameters k/e) and an inner
/// row (`inner`, parameters i/m for i = 1…m−1), both running the same way. `flip` reverses
/// the winding (top and left sides).
fn zipper(outer: &[u32], inner: &[u32], m: u32, flip: bool, tris: &mut Vec<[u32; 3]>) {
    let e = outer.len() - 1;
    let last = inner.len() - 1;
    let (mut k, mut j) = (0usize, 0usize);
    let mut emit = |a: u32, b: u32, c: u32| {
        tris.push(if flip { [a, c, b] } else { [a, b, c] });
    };
    while k < e || j < last {
        let advance_outer = if k == e {
            false
        } else if j == last {
            true
        } else {
            // Compare midpoints of the candidate segments (in parameter, ×2·e·m to stay exact).
            let outer_mid = (2 * k as u64 + 1) * m as u64;
            let inner_mid = (2 * j as u64 + 3) * e as u64;
            outer_mid <= inner_mid
        };
        if advance_outer {
            emit(outer[k], outer[k + 1], inner[j]);
            k += 1;
        } else {
            emit(outer[k], inner[j + 1], inner[j]);
            j += 1;
        }
    }
}

/// Removes triangles that repeat a welded vertex (collapsed edges at poles and apexes).
fn drop_degenerate(out: &mut PatchOut) {
    let gid = &out.gid;
    out.tris.retain(|t| {
        let (a, b, c) = (gid[t[0] as usize], gid[t[1] as usize], gid[t[2] as usize]);
        a != b && b != c && a != c
    });
}

/// Concatenates patch outputs into one mesh; recomputes normals on displaced meshes.
fn assemble(outs: Vec<PatchOut>, welded: usize, displaced: bool, derivs: bool) -> Tessellation {
    let welded_normals = displaced.then(|| {
        let mut acc = vec![DVec3::ZERO; welded];
        for o in &outs {
            for t in &o.tris {
                let [a, b, c] = t.map(|i| o.pos[i as usize]);
                let n = (b - a).cross(c - a); // length = 2·area: area weighting
                for &i in t {
                    acc[o.gid[i as usize] as usize] += n;
                }
            }
        }
        acc
    });
    let verts: usize = outs.iter().map(|o| o.gid.len()).sum();
    let tri_count: usize = outs.iter().map(|o| o.tris.len()).sum();
    let mut mesh = TriMesh {
        positions: Vec::with_capacity(verts),
        normals: Some(Vec::with_capacity(verts)),
        uvs: Some(Vec::with_capacity(verts)),
        triangles: Vec::with_capacity(tri_count),
    };
    let mut d = derivs.then(|| SurfaceDerivatives {
        dpdu: Vec::with_capacity(verts),
        dpdv: Vec::with_capacity(verts),
    });
    let normals = mesh.normals.as_mut().expect("set above");
    let uvs = mesh.uvs.as_mut().expect("set above");
    for o in &outs {
        let base = mesh.positions.len() as u32;
        for (i, &gid) in o.gid.iter().enumerate() {
            mesh.positions.push(o.pos[i].as_vec3());
            let n = match &welded_normals {
                Some(w) => w[gid as usize].try_normalize().unwrap_or(o.n[i]),
                None => o.n[i],
            };
            normals.push(n.as_vec3());
            uvs.push(o.uv[i].as_vec2());
        }
        if let Some(d) = d.as_mut() {
            d.dpdu.extend(o.dpdu.iter().map(|v| v.as_vec3()));
            d.dpdv.extend(o.dpdv.iter().map(|v| v.as_vec3()));
        }
        mesh.triangles
            .extend(o.tris.iter().map(|t| t.map(|i| i + base)));
    }
    Tessellation {
        mesh,
        derivatives: d,
    }
}

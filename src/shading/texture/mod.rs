//! Texture shaders and shader graphs: the nodes a material parameter may be driven by, and
//! the compiled graphs materials carry.
//!
//! A scene's node trees (and the phenomena they call) are compiled by the loader
//! (`scene::nodes`) into one flat [`Program`] per material: a list of [`Op`]s in dependency
//! order, each writing one register. Every register holds an RGB triple; a scalar is stored
//! in all three channels (so a scalar may feed a colour input, never the other way round —
//! the loader checks types). At a shading point the program runs once with the point's
//! [`Inputs`]; the bound parameters are written into a copy of the material's constant
//! shader ([`bind`]), so BSDFs see plain constants.
//!
//! Node families, one file each: [`pattern`] (checker, disk, stairs, smoothstep, uv repeat),
//! [`noise`] (Perlin, fBm, turbulence), [`image`] (PNG/EXR textures), [`colour`]
//! (RGB/HSV/HSL), [`bump`] (bump mapping and the shading-normal safeguards). Everything is
//! deterministic: a node's value depends only on its inputs and parameters.

pub mod bind;
pub mod bump;
pub mod colour;
pub mod exr_channels;
pub mod hit;
pub mod image;
pub mod noise;
pub mod normal_map;
pub mod object_normal;
pub use crate::pattern;

use glam::{Vec2, Vec3};

pub use crate::components::graph::{
    Binding, BumpMap, MaterialGraph, NoiseKind, NormalMap, Op, Program, Reg,
};
use crate::components::Shader;

/// What a graph may read at a shading point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inputs {
    /// Texture coordinates.
    pub uv: Vec2,
    /// Object-space position.
    pub p: Vec3,
    /// World-space unit shading normal (before bump mapping).
    pub n: Vec3,
    /// The mesh's interpolated vertex colour (linear RGB; white without vertex colours).
    pub colour: Vec3,
}

impl Program {
    /// Runs every op; `regs` receives one value per op (finite: NaN/∞ become 0).
    pub fn run(&self, inputs: &Inputs, regs: &mut Vec<Vec3>) {
        self.run_to(inputs, regs, self.ops.len());
    }

    /// Runs the first `end` ops (enough for every register below `end`: ops only read
    /// earlier registers).
    pub fn run_to(&self, inputs: &Inputs, regs: &mut Vec<Vec3>, end: usize) {
        regs.clear();
        regs.reserve(end);
        for op in &self.ops[..end.min(self.ops.len())] {
            let r = |i: &Reg| regs[*i as usize];
            let s = |i: &Reg| regs[*i as usize].x;
            let uv = |i: &Reg| {
                let c = regs[*i as usize];
                Vec2::new(c.x, c.y)
            };
            let v = match op {
                Op::Const(c) => *c,
                Op::Uv => inputs.uv.extend(0.0),
                Op::Position => inputs.p,
                Op::Normal => inputs.n,
                Op::VertexColour => inputs.colour,
                Op::Checker { uv: c, scale, a, b } => {
                    if pattern::checker(uv(c), s(scale)) == 0.0 {
                        r(a)
                    } else {
                        r(b)
                    }
                }
                Op::Disk {
                    uv: c,
                    center,
                    radius,
                    fuzz,
                    inside,
                    outside,
                } => {
                    let t = pattern::disk(uv(c), *center, s(radius), s(fuzz));
                    pattern::mix(r(outside), r(inside), t)
                }
                Op::Steps { uv: c, steps, fuzz } => {
                    Vec3::splat(pattern::steps(uv(c).y, s(steps), s(fuzz)))
                }
                Op::Repeat { uv: c, scale } => pattern::repeat(uv(c), s(scale)).extend(0.0),
                Op::Noise { p, kind, fractal } => Vec3::splat(match kind {
                    NoiseKind::Perlin => noise::noise(r(p), fractal.frequency, fractal.seed),
                    NoiseKind::Fbm => noise::fbm(r(p), fractal),
                    NoiseKind::Turbulence => noise::turbulence(r(p), fractal),
                }),
                Op::Image { uv: c, texture } => texture.sample(uv(c)),
                Op::ImageAlpha { uv: c, texture } => Vec3::splat(texture.sample_alpha(uv(c))),
                Op::Mix { a, b, t } => pattern::mix(r(a), r(b), s(t)),
                Op::Smoothstep { edge0, edge1, x } => {
                    Vec3::splat(pattern::smoothstep(s(edge0), s(edge1), s(x)))
                }
                Op::Add(a, b) => r(a) + r(b),
                Op::Sub(a, b) => r(a) - r(b),
                Op::Mul(a, b) => r(a) * r(b),
                Op::Channel(a, k) => Vec3::splat(r(a)[(*k).min(2) as usize]),
                Op::Luminance(a) => Vec3::splat(r(a).dot(Vec3::new(0.2126, 0.7152, 0.0722))),
                Op::Combine(a, b, c) => Vec3::new(s(a), s(b), s(c)),
                Op::Convert { input, from, to } => colour::convert(r(input), *from, *to),
            };
            regs.push(Vec3::select(v.is_finite_mask(), v, Vec3::ZERO));
        }
    }
}

/// Step in uv (or, without a uv parametrisation, in object units along the tangents) of the
/// finite differences that give the height's derivatives.
pub const BUMP_STEP: f32 = 1e-3;

impl MaterialGraph {
    /// `shader` with every bound parameter replaced by its value at `inputs`; `regs` is
    /// scratch space, which holds every register afterwards when the graph
    /// [`MaterialGraph::runs_at_hits`] (the normal map and emission read them).
    pub fn bind(&self, shader: &Shader, inputs: &Inputs, regs: &mut Vec<Vec3>) -> Shader {
        let mut out = shader.clone();
        if !self.runs_at_hits() {
            return out;
        }
        self.program.run(inputs, regs);
        for b in &self.bindings {
            let v = regs[b.reg as usize];
            bind::field(&mut out, &b.param, |f| f.set(v));
        }
        out
    }

    /// The material's bump height (object units along the normal) at `inputs`; 0 without
    /// a bump map.
    pub fn bump_height(&self, inputs: &Inputs, regs: &mut Vec<Vec3>) -> f32 {
        match self.bump {
            Some(bump) => {
                self.program.run_to(inputs, regs, bump.height as usize + 1);
                regs[bump.height as usize].x * bump.scale
            }
            None => 0.0,
        }
    }
}

/// The bump-mapped shading normal at `inputs` (its `n` is the unperturbed unit normal) for
/// the height function `height` (called first at `inputs` itself, then at the two offset
/// points), from the surface tangents `[∂P/∂u, ∂P/∂v]` in world space
/// followed by their object-space counterparts (how the `Position` input moves). `has_uv`:
/// the tangents follow the uv parametrisation (else uv stays fixed in the differences).
pub fn bumped_normal(
    inputs: &Inputs,
    tangents: [Vec3; 4],
    has_uv: bool,
    mut height: impl FnMut(&Inputs) -> f32,
) -> Vec3 {
    let [dpdu, dpdv, dpdu_obj, dpdv_obj] = tangents;
    let h = height(inputs);
    let d = BUMP_STEP;
    let du_uv = if has_uv {
        Vec2::new(d, 0.0)
    } else {
        Vec2::ZERO
    };
    let dv_uv = if has_uv {
        Vec2::new(0.0, d)
    } else {
        Vec2::ZERO
    };
    let hu = height(&Inputs {
        uv: inputs.uv + du_uv,
        p: inputs.p + dpdu_obj * d,
        ..*inputs
    });
    let hv = height(&Inputs {
        uv: inputs.uv + dv_uv,
        p: inputs.p + dpdv_obj * d,
        ..*inputs
    });
    bump::perturb(inputs.n, dpdu, dpdv, (hu - h) / d, (hv - h) / d)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inputs(u: f32, v: f32) -> Inputs {
        Inputs {
            uv: Vec2::new(u, v),
            p: Vec3::ZERO,
            n: Vec3::Z,
            colour: Vec3::ONE,
        }
    }

    #[test]
    fn checker_graph_binds_albedo() {
        let mut p = Program::default();
        let uv = p.push(Op::Uv);
        let scale = p.push(Op::Const(Vec3::splat(2.0)));
        let a = p.push(Op::Const(Vec3::splat(0.9)));
        let b = p.push(Op::Const(Vec3::splat(0.1)));
        let c = p.push(Op::Checker { uv, scale, a, b });
        let g = MaterialGraph {
            program: p,
            bindings: vec![Binding {
                param: "albedo".into(),
                reg: c,
            }],
            bump: None,
            normal_map: None,
            object_normal: None,
            emission: None,
        };
        let base = Shader::Lambert { albedo: Vec3::ONE };
        let mut regs = Vec::new();
        let at = |u, v, regs: &mut Vec<Vec3>| match g.bind(&base, &inputs(u, v), regs) {
            Shader::Lambert { albedo } => albedo.x,
            _ => unreachable!(),
        };
        assert_eq!(at(0.1, 0.1, &mut regs), 0.9);
        assert_eq!(at(0.6, 0.1, &mut regs), 0.1);
        assert_eq!(at(0.6, 0.6, &mut regs), 0.9);
    }

    #[test]
    fn bump_of_a_linear_height_tilts_the_normal() {
        // h = 0.5·u on a plane with ∂P/∂u = x: normal ∝ (−0.5, 0, 1).
        let mut p = Program::default();
        let uv = p.push(Op::Uv);
        let u = p.push(Op::Channel(uv, 0));
        let g = MaterialGraph {
            program: p,
            bindings: Vec::new(),
            bump: Some(BumpMap {
                height: u,
                scale: 0.5,
            }),
            normal_map: None,
            object_normal: None,
            emission: None,
        };
        let t = [Vec3::X, Vec3::Y, Vec3::X, Vec3::Y];
        let mut regs = Vec::new();
        let n = bumped_normal(&inputs(0.3, 0.3), t, true, |i| g.bump_height(i, &mut regs));
        assert!(
            (n - Vec3::new(-0.5, 0.0, 1.0).normalize()).length() < 1e-3,
            "{n}"
        );
    }
}

//! BSDFs in the local shading frame (normal = +Z, `wo` on the +Z side), built from a
//! material's [`Shader`].
//!
//! A [`Bsdf`] is a weighted sum of up to [`MAX_LOBES`] lobes (one file per family):
//! Lambert ([`diffuse`]), modified Phong ([`phong`]), microfacet reflection ([`glossy`]),
//! the glTF metallic-roughness model ([`metallic_roughness`]) and the delta lobes ([`specular`]: mirror, smooth dielectric, pass-through).
//!
//! **Energy.** Lobe weights are colours. If the weights of a material add up to more than 1 in
//! a channel, all weights of that channel are divided by their sum. Every lobe alone reflects
//! at most what it receives (Lambert: 1; normalised Phong: ≤ 1; microfacet with V-cavity
//! masking and Fresnel ≤ 1: ≤ 1; mirror: 1; dielectric: R + T = 1), so every material does.
//!
//! **Sampling.** A lobe is chosen with probability proportional to the largest channel of
//! its weight, then sampled. [`Bsdf::pdf`] and [`Bsdf::eval`] cover the non-delta lobes
//! only; a delta sample reports `delta = true` and `f` such that `f·|cosθi|/pdf` is its
//! throughput weight.

pub mod diffuse;
pub mod glossy;
pub mod metallic_roughness;
pub mod phong;
pub mod specular;

use glam::{Vec2, Vec3};

use self::glossy::Fresnel;
use self::specular::DeltaBranch;
pub use self::specular::TransportMode;
use crate::components::{PhotonShader, Shader};
use crate::shading::microfacet::Distribution;

/// Most lobes a material has (`dgs` inside `Opacity`: diffuse, glossy, mirror, pass-through).
pub const MAX_LOBES: usize = 4;

/// One scattering lobe, unweighted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Lobe {
    /// Ideal diffuse.
    Lambert,
    /// Modified Phong about the mirror direction.
    Phong {
        /// Exponent.
        exponent: f32,
    },
    /// Microfacet reflection.
    Glossy {
        /// Distribution of microfacet normals.
        dist: Distribution,
        /// Fresnel factor.
        fresnel: Fresnel,
    },
    /// The glTF metallic-roughness BRDF (GGX specular, Schlick Fresnel, diffuse base).
    MetallicRoughness(metallic_roughness::MetallicRoughness),
    /// Perfect mirror (delta).
    Mirror,
    /// Smooth dielectric interface (delta reflection + refraction).
    Dielectric {
        /// `η` behind the surface over `η` on the side of `wo`.
        eta: f32,
    },
    /// Straight pass-through (delta transmission): what lies behind.
    PassThrough,
}

impl Lobe {
    /// Whether the lobe is a Dirac delta.
    pub fn is_delta(&self) -> bool {
        matches!(
            self,
            Lobe::Mirror | Lobe::Dielectric { .. } | Lobe::PassThrough
        )
    }

    fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match self {
            Lobe::Lambert => Vec3::splat(diffuse::eval(wo, wi)),
            Lobe::Phong { exponent } => Vec3::splat(phong::eval(*exponent, wo, wi)),
            Lobe::Glossy { dist, fresnel } => glossy::eval(dist, fresnel, wo, wi),
            Lobe::MetallicRoughness(m) => metallic_roughness::eval(m, wo, wi),
            _ => Vec3::ZERO,
        }
    }

    fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self {
            Lobe::Lambert => diffuse::pdf(wo, wi),
            Lobe::Phong { exponent } => phong::pdf(*exponent, wo, wi),
            Lobe::Glossy { dist, .. } => glossy::pdf(dist, wo, wi),
            Lobe::MetallicRoughness(m) => metallic_roughness::pdf(m, wo, wi),
            _ => 0.0,
        }
    }
}

/// How a sampled direction leaves the surface (for per-ray-type trace depths).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scatter {
    /// Diffuse reflection.
    Diffuse,
    /// Glossy or perfect-mirror reflection (counts against the reflection depth).
    Reflection,
    /// Refraction or pass-through (counts against the refraction depth).
    Transmission,
}

/// A sampled direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BsdfSample {
    /// Local direction toward the incident light.
    pub wi: Vec3,
    /// BSDF value (delta: the value whose `f·|cosθi|/pdf` is the throughput weight).
    pub f: Vec3,
    /// Solid-angle pdf (delta: the discrete probability of the branch, times lobe choice).
    pub pdf: f32,
    /// Whether the direction came from a delta lobe.
    pub delta: bool,
    /// Kind of scattering.
    pub scatter: Scatter,
    /// Whether the direction is the straight pass-through of a partly transparent surface
    /// (`Opacity`): the ray goes on unbent, as a shadow ray crossing the surface does.
    pub pass_through: bool,
}

impl BsdfSample {
    /// Throughput weight `f·|cosθi|/pdf`.
    pub fn weight(&self) -> Vec3 {
        self.f * (self.wi.z.abs() / self.pdf)
    }
}

/// A delta branch with its colour weight, for integrators that trace every branch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WeightedBranch {
    /// Local direction toward the incident light.
    pub wi: Vec3,
    /// Radiance fraction per channel.
    pub weight: Vec3,
    /// Whether the branch crosses the surface.
    pub transmits: bool,
}

/// A material's BSDF at one shading point, in the local frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Bsdf {
    lobes: [(Vec3, Lobe); MAX_LOBES],
    len: usize,
    /// Lobe choice probabilities (sum 1 over `len` lobes).
    prob: [f32; MAX_LOBES],
}

impl Bsdf {
    /// The BSDF of `shader` seen from the front (`front = true`) or back face. `None` for
    /// shaders that do not integrate light (`Constant`, `DefaultSurface`) or that reflect
    /// nothing. Of a `Local` model only its mirror term is a lobe.
    #[inline]
    pub fn new(shader: &Shader, front: bool) -> Option<Self> {
        let mut b = Self::empty();
        b.set_shader(shader, front).then_some(b)
    }

    /// A BSDF without lobes (it reflects nothing), to be filled by [`Bsdf::set_shader`].
    pub const fn empty() -> Self {
        Self {
            lobes: [(Vec3::ZERO, Lobe::Lambert); MAX_LOBES],
            len: 0,
            prob: [0.0; MAX_LOBES],
        }
    }

    /// Makes this the BSDF [`Bsdf::new`] gives for `shader` and `front`, in place; false
    /// (and no lobes) where `new` gives `None`. Hot loops keep one value and refill it, so
    /// the 168-byte value is not moved into an `Option` and out again (a copy whose length
    /// field was then read back through a stalled store, 2 % of a path-traced sample).
    #[inline]
    pub fn set_shader(&mut self, shader: &Shader, front: bool) -> bool {
        self.len = 0;
        self.push_shader(shader, Vec3::ONE, front);
        if !self.finish() {
            self.len = 0;
        }
        self.len > 0
    }

    /// Whether this BSDF has a lobe (reflects or transmits something); false exactly where
    /// [`Bsdf::new`] gives `None`.
    #[inline]
    pub fn reflects(&self) -> bool {
        self.len > 0
    }

    /// What photons scatter by at a material with the photon shader `p`, seen from the front
    /// (`front = true`) or back face: a mirror lobe weighted by `p.specular` and a smooth
    /// dielectric of index `p.ior` weighted by `p.refraction` (energy clamp applied). It may
    /// have no lobe (`p` absorbs every photon; [`Bsdf::reflects`] is then false).
    pub fn for_photons(p: &PhotonShader, front: bool) -> Self {
        let mut b = Self::empty();
        b.push(p.specular, Lobe::Mirror);
        let eta = if front { p.ior } else { 1.0 / p.ior };
        b.push(p.refraction, Lobe::Dielectric { eta });
        if !b.finish() {
            b.len = 0;
        }
        b
    }

    /// A BSDF made of the given weighted lobes (energy clamp and probabilities applied).
    pub fn from_lobes(lobes: &[(Vec3, Lobe)]) -> Option<Self> {
        let mut b = Self {
            lobes: [(Vec3::ZERO, Lobe::Lambert); MAX_LOBES],
            len: 0,
            prob: [0.0; MAX_LOBES],
        };
        for &(w, l) in lobes {
            b.push(w, l);
        }
        b.finish().then_some(b)
    }

    fn push(&mut self, weight: Vec3, lobe: Lobe) {
        if weight.max_element() <= 0.0 {
            return;
        }
        if let Some(slot) = self.lobes[..self.len].iter_mut().find(|(_, l)| *l == lobe) {
            slot.0 += weight;
            return;
        }
        if self.len < MAX_LOBES {
            self.lobes[self.len] = (weight, lobe);
            self.len += 1;
        }
    }

    fn push_shader(&mut self, shader: &Shader, w: Vec3, front: bool) {
        let spec = |roughness: f32| Lobe::Glossy {
            dist: Distribution::BlinnPhong {
                exponent: 1.0 / roughness.max(1e-4),
            },
            fresnel: Fresnel::One,
        };
        match shader {
            Shader::Constant { .. } | Shader::DefaultSurface { .. } => {}
            Shader::Lambert { albedo } => self.push(w * *albedo, Lobe::Lambert),
            Shader::Phong {
                diffuse,
                specular,
                spec_exp,
                ..
            } => {
                self.push(w * *diffuse, Lobe::Lambert);
                self.push(
                    w * *specular,
                    Lobe::Phong {
                        exponent: *spec_exp,
                    },
                );
            }
            Shader::Blinn {
                diffuse,
                specular,
                roughness,
                ior,
                ..
            } => {
                self.push(w * *diffuse, Lobe::Lambert);
                self.push(
                    w * *specular,
                    Lobe::Glossy {
                        dist: Distribution::Beckmann { alpha: *roughness },
                        fresnel: Fresnel::Dielectric(Vec3::splat(*ior)),
                    },
                );
            }
            Shader::CookTorrance {
                diffuse,
                specular,
                roughness,
                ior,
                ..
            } => {
                self.push(w * *diffuse, Lobe::Lambert);
                self.push(
                    w * *specular,
                    Lobe::Glossy {
                        dist: Distribution::Beckmann { alpha: *roughness },
                        fresnel: Fresnel::Dielectric(*ior),
                    },
                );
            }
            Shader::Blong {
                diffuse,
                specular,
                spec_exp,
                ..
            } => {
                self.push(w * *diffuse, Lobe::Lambert);
                self.push(
                    w * *specular,
                    Lobe::Glossy {
                        dist: Distribution::BlinnPhong {
                            exponent: *spec_exp,
                        },
                        fresnel: Fresnel::One,
                    },
                );
            }
            Shader::FresnelSpecular {
                diffuse,
                specular,
                spec_exp,
                ior_in,
                ior_out,
                ..
            } => {
                self.push(w * *diffuse, Lobe::Lambert);
                self.push(
                    w * *specular,
                    Lobe::Glossy {
                        dist: Distribution::BlinnPhong {
                            exponent: *spec_exp,
                        },
                        fresnel: Fresnel::Dielectric(Vec3::splat(ior_in / ior_out)),
                    },
                );
            }
            Shader::Matte { kd, color, .. } => self.push(w * *kd * *color, Lobe::Lambert),
            Shader::Plastic {
                kd,
                ks,
                roughness,
                specular_color,
                color,
                ..
            }
            | Shader::PaintedPlastic {
                kd,
                ks,
                roughness,
                specular_color,
                color,
                ..
            } => {
                self.push(w * *kd * *color, Lobe::Lambert);
                self.push(w * *ks * *specular_color, spec(*roughness));
            }
            Shader::Metal {
                ks,
                roughness,
                color,
                ..
            } => self.push(w * *ks * *color, spec(*roughness)),
            Shader::ShinyMetal {
                ks,
                kr,
                roughness,
                color,
                ..
            } => {
                self.push(w * *ks * *color, spec(*roughness));
                self.push(w * *kr * *color, Lobe::Mirror);
            }
            Shader::Mirror { color } => self.push(w * *color, Lobe::Mirror),
            Shader::MetallicRoughness {
                base_color,
                metallic,
                roughness,
            } => {
                use metallic_roughness::{MetallicRoughness, DIELECTRIC_F0, SMOOTH_ROUGHNESS};
                let base = base_color.clamp(Vec3::ZERO, Vec3::ONE);
                let metallic = metallic.clamp(0.0, 1.0);
                if *roughness < SMOOTH_ROUGHNESS {
                    let diffuse = base * ((1.0 - metallic) * (1.0 - DIELECTRIC_F0));
                    self.push(w * diffuse, Lobe::Lambert);
                    let mirror = base * metallic + Vec3::splat((1.0 - metallic) * DIELECTRIC_F0);
                    self.push(w * mirror, Lobe::Mirror);
                } else {
                    let r = roughness.min(1.0);
                    let lobe = MetallicRoughness {
                        base,
                        metallic,
                        alpha: r * r,
                    };
                    self.push(w, Lobe::MetallicRoughness(lobe));
                }
            }
            // Only the traced mirror term is a lobe; the rest is evaluated as written
            // (`crate::shading::local`).
            Shader::Local(m) => self.push(w * m.reflection, Lobe::Mirror),
            Shader::Dielectric { ior, ior_out, .. } => {
                let eta = if front { ior / ior_out } else { ior_out / ior };
                self.push(w, Lobe::Dielectric { eta });
            }
            Shader::Dgs {
                diffuse,
                glossy,
                specular,
                shiny,
            } => {
                self.push(w * *diffuse, Lobe::Lambert);
                self.push(
                    w * *glossy,
                    Lobe::Glossy {
                        dist: Distribution::BlinnPhong { exponent: *shiny },
                        fresnel: Fresnel::One,
                    },
                );
                self.push(w * *specular, Lobe::Mirror);
            }
            Shader::Opacity { opacity, input } => {
                let o = opacity.clamp(Vec3::ZERO, Vec3::ONE);
                self.push_shader(input, w * o, front);
                self.push(w * (Vec3::ONE - o), Lobe::PassThrough);
            }
        }
    }

    /// Applies the energy clamp and sets the lobe probabilities in place; false when nothing
    /// is reflected.
    fn finish(&mut self) -> bool {
        if self.len == 0 {
            return false;
        }
        let sum = self.lobes[..self.len]
            .iter()
            .fold(Vec3::ZERO, |s, (w, _)| s + *w);
        let scale = Vec3::ONE / sum.max(Vec3::ONE);
        for (w, _) in &mut self.lobes[..self.len] {
            *w *= scale;
        }
        let total: f32 = self.lobes[..self.len]
            .iter()
            .map(|(w, _)| w.max_element())
            .sum();
        if total <= 0.0 {
            return false;
        }
        for i in 0..self.len {
            self.prob[i] = self.lobes[i].0.max_element() / total;
        }
        true
    }

    /// The weighted lobes (after the energy clamp).
    pub fn lobes(&self) -> &[(Vec3, Lobe)] {
        &self.lobes[..self.len]
    }

    /// Whether some lobe is not a delta (light sampling can contribute).
    pub fn has_non_delta(&self) -> bool {
        self.lobes().iter().any(|(_, l)| !l.is_delta())
    }

    /// Whether some lobe is a delta (needs traced reflection/refraction rays).
    pub fn has_delta(&self) -> bool {
        self.lobes().iter().any(|(_, l)| l.is_delta())
    }

    /// The weight of the only lobe of a BSDF that is one Lambert lobe chosen with probability
    /// exactly 1 (the common diffuse material), for the fast paths of [`Bsdf::eval`],
    /// [`Bsdf::pdf`] and [`Bsdf::sample`]; `None` for every other BSDF.
    #[inline(always)]
    fn lambert_only(&self) -> Option<Vec3> {
        (self.len == 1 && matches!(self.lobes[0].1, Lobe::Lambert) && self.prob[0] == 1.0)
            .then_some(self.lobes[0].0)
    }

    /// BSDF value of the non-delta lobes for light arriving from `wi` and leaving along `wo`.
    ///
    /// A lone Lambert lobe is evaluated directly: the same operations as the sum over the
    /// lobes (`0 + w·f`, the zero kept so a `−0` weight still gives `+0`), without the lobe
    /// dispatch ([`Bsdf::eval_lobes`]).
    #[inline(always)]
    pub fn eval(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        match self.lambert_only() {
            Some(w) => Vec3::ZERO + w * Vec3::splat(diffuse::eval(wo, wi)),
            None => self.eval_lobes(wo, wi),
        }
    }

    /// [`Bsdf::eval`] as the sum over the lobes (every BSDF).
    #[inline]
    fn eval_lobes(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.lobes()
            .iter()
            .fold(Vec3::ZERO, |s, (w, l)| s + *w * l.eval(wo, wi))
    }

    /// The diffuse share of [`Bsdf::eval`]: the Lambert lobes and the diffuse base of a
    /// metallic-roughness lobe (the rest is glossy), for component passes.
    pub fn eval_diffuse(&self, wo: Vec3, wi: Vec3) -> Vec3 {
        self.lobes().iter().fold(Vec3::ZERO, |s, (w, l)| match l {
            Lobe::Lambert => s + *w * l.eval(wo, wi),
            Lobe::MetallicRoughness(m) => s + *w * metallic_roughness::eval_diffuse(m, wo, wi),
            _ => s,
        })
    }

    /// Solid-angle pdf with which [`Bsdf::sample`] returns the non-delta direction `wi`.
    ///
    /// A lone Lambert lobe (probability 1) gives its own pdf: the sum `1·p` over one lobe is
    /// `p` bit for bit (`p ≥ +0`), so no lobe dispatch is needed ([`Bsdf::pdf_lobes`]).
    #[inline(always)]
    pub fn pdf(&self, wo: Vec3, wi: Vec3) -> f32 {
        match self.lambert_only() {
            Some(_) => diffuse::pdf(wo, wi),
            None => self.pdf_lobes(wo, wi),
        }
    }

    /// [`Bsdf::pdf`] as the probability-weighted sum over the lobes (every BSDF).
    #[inline]
    fn pdf_lobes(&self, wo: Vec3, wi: Vec3) -> f32 {
        self.lobes()
            .iter()
            .zip(&self.prob)
            .map(|((_, l), p)| p * l.pdf(wo, wi))
            .sum()
    }

    /// Draws a direction from `u ∈ [0,1)³` (`u.x` chooses the lobe and, re-used, a
    /// dielectric's branch). `None` when the chosen lobe produced no valid direction.
    ///
    /// A lone Lambert lobe is sampled inline in the caller ([`Bsdf::sample_lambert`], the
    /// same bits as [`Bsdf::sample_transport`]); other BSDFs go through the general sampler,
    /// which stays a call.
    #[inline(always)]
    pub fn sample(&self, wo: Vec3, u: Vec3) -> Option<BsdfSample> {
        match self.lambert_only() {
            Some(w) => Self::sample_lambert(w, wo, u),
            None => self.sample_general(wo, u),
        }
    }

    /// [`Bsdf::sample`] of a BSDF that is one Lambert lobe of weight `w` and probability 1:
    /// what [`Bsdf::sample_transport`] computes for it, without the lobe choice (its `u.x`
    /// remap is unused by a Lambert lobe) and the dispatch. The pdf and value are those of
    /// [`Bsdf::pdf`] and [`Bsdf::eval`] (see there why they are the same bits).
    #[inline(always)]
    fn sample_lambert(w: Vec3, wo: Vec3, u: Vec3) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let wi = diffuse::sample(wo, Vec2::new(u.y, u.z))?;
        let pdf = diffuse::pdf(wo, wi);
        let f = Vec3::ZERO + w * Vec3::splat(diffuse::eval(wo, wi));
        crate::sampling::usable_pdf(pdf).then_some(BsdfSample {
            wi,
            f,
            pdf,
            delta: false,
            scatter: Scatter::Diffuse,
            pass_through: false,
        })
    }

    /// [`Bsdf::sample`] for any BSDF (radiance transport).
    #[inline(never)]
    fn sample_general(&self, wo: Vec3, u: Vec3) -> Option<BsdfSample> {
        self.sample_transport(wo, u, TransportMode::Radiance)
    }

    /// [`Bsdf::sample`] for the given transported quantity (photon tracing samples with
    /// [`TransportMode::Importance`]; `wo` is then the direction the photon came from).
    #[inline(always)]
    pub fn sample_transport(&self, wo: Vec3, u: Vec3, mode: TransportMode) -> Option<BsdfSample> {
        if wo.z <= 0.0 {
            return None;
        }
        let mut acc = 0.0;
        let mut k = self.len - 1;
        for i in 0..self.len {
            if u.x < acc + self.prob[i] || i == self.len - 1 {
                k = i;
                break;
            }
            acc += self.prob[i];
        }
        let p = self.prob[k];
        let uc = if p > 0.0 {
            ((u.x - acc) / p).clamp(0.0, 1.0 - f32::EPSILON)
        } else {
            0.0
        };
        let u2 = Vec2::new(u.y, u.z);
        let (w, lobe) = self.lobes[k];
        let pass_through = matches!(lobe, Lobe::PassThrough);
        let delta = |b: DeltaBranch, prob: f32| {
            let cos = b.wi.z.abs();
            (cos > 0.0 && prob > 0.0).then(|| BsdfSample {
                wi: b.wi,
                f: w * (b.weight / cos),
                pdf: p * prob,
                delta: true,
                scatter: if b.transmits {
                    Scatter::Transmission
                } else {
                    Scatter::Reflection
                },
                pass_through,
            })
        };
        let wi = match lobe {
            Lobe::Mirror => return delta(specular::mirror(wo), 1.0),
            Lobe::PassThrough => return delta(specular::pass_through(wo), 1.0),
            Lobe::Dielectric { eta } => {
                let (branch, prob) = specular::dielectric_sample(wo, eta, mode, uc);
                return delta(branch, prob);
            }
            Lobe::Lambert => diffuse::sample(wo, u2)?,
            Lobe::Phong { exponent } => phong::sample(exponent, wo, u2)?,
            Lobe::Glossy { dist, .. } => glossy::sample(&dist, wo, u2)?,
            Lobe::MetallicRoughness(m) => metallic_roughness::sample(&m, wo, u2)?,
        };
        let pdf = self.pdf_lobes(wo, wi);
        let f = self.eval_lobes(wo, wi);
        crate::sampling::usable_pdf(pdf).then_some(BsdfSample {
            wi,
            f,
            pdf,
            delta: false,
            scatter: if matches!(lobe, Lobe::Lambert) {
                Scatter::Diffuse
            } else {
                Scatter::Reflection
            },
            pass_through: false,
        })
    }

    /// Every delta branch with its colour weight (a dielectric gives its reflected and
    /// refracted branches), for integrators that trace all of them.
    pub fn delta_branches(&self, wo: Vec3) -> impl Iterator<Item = WeightedBranch> + '_ {
        let mut out = [None; MAX_LOBES + 1];
        let mut n = 0;
        if wo.z > 0.0 {
            for &(w, lobe) in self.lobes() {
                let mut add = |b: DeltaBranch| {
                    if b.weight > 0.0 && n < out.len() {
                        out[n] = Some(WeightedBranch {
                            wi: b.wi,
                            weight: w * b.weight,
                            transmits: b.transmits,
                        });
                        n += 1;
                    }
                };
                match lobe {
                    Lobe::Mirror => add(specular::mirror(wo)),
                    Lobe::PassThrough => add(specular::pass_through(wo)),
                    Lobe::Dielectric { eta } => {
                        let (r, t) = specular::dielectric(wo, eta);
                        add(r);
                        if let Some(t) = t {
                            add(t);
                        }
                    }
                    _ => {}
                }
            }
        }
        out.into_iter().flatten()
    }
}

#[cfg(test)]
mod fast_path_tests;

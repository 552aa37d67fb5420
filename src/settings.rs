//! Render settings: the scene's `options` after command-line overrides.

/// The widest Gaussian pixel filter (truncation radius, pixels): a wider one spreads each
/// pixel's samples over more of the frame than it covers (issue 18, family 8).
pub const MAX_FILTER_RADIUS: f64 = 64.0;

/// Pixel reconstruction filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PixelFilter {
    /// Unweighted average of samples inside the pixel.
    Box,
    /// Gaussian of standard deviation `sigma` pixels, truncated at `radius` pixels; samples are
    /// importance-sampled from the filter so every sample has weight one.
    Gaussian {
        /// Standard deviation in pixels.
        sigma: f32,
        /// Truncation radius in pixels.
        radius: f32,
    },
}

/// Which faces of one-sided surfaces are visible to rays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Face {
    /// Only front faces (counter-clockwise) are shaded; back faces of one-sided materials
    /// render black but still block light.
    Front,
    /// Every surface is treated as two-sided.
    Both,
    /// Back faces of one-sided materials are left out of the rays altogether (mental ray's
    /// `face front`, RenderMan's `Sides 1`): camera, shadow, reflection, refraction,
    /// gathering and photon rays go on through them as if they were not there
    /// (`build_accel` marks their triangles [`crate::components::FRONT_ONLY`]). Ambient
    /// occlusion bakes still see them.
    Cull,
}

/// BVH build quality: more time building for faster tracing.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BvhQuality {
    /// Cheapest build.
    Fast,
    /// Balanced (default).
    Medium,
    /// Slowest build, best hierarchy.
    High,
}

/// How the `shade` stage computes radiance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Integrator {
    /// Direct lighting from every light (shadow rays), emission, and perfect mirror and
    /// refraction rays traced recursively (every delta branch, no sampling among them) up to
    /// the trace depths. Glossy and diffuse interreflection is not computed.
    Direct,
    /// Unbiased path tracing: next-event estimation and BSDF sampling combined with multiple
    /// importance sampling (power heuristic), Russian roulette; truncated only by the trace
    /// depths. The reference the approximations are measured against.
    Path,
}

/// Adaptive anti-aliasing (mental ray `samples min max` with a `contrast`): every pixel
/// takes `min` samples, then doubles its count until the standard error of its mean (sample
/// standard deviation / √n) is at most `contrast` in every channel, or `max` is reached.
/// Each pixel decides from its own samples only, so the image does not depend on the
/// thread count.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AdaptiveSamples {
    /// Samples every pixel takes (≥ 1).
    pub min: u32,
    /// Most samples one pixel takes (≥ `min`).
    pub max: u32,
    /// Per-channel threshold on the standard error of the pixel mean (radiance units).
    pub contrast: glam::Vec3,
}

/// Settings every stage can read.
#[derive(Debug, Clone, PartialEq)]
pub struct RenderSettings {
    /// Samples per pixel (when `adaptive` is `None`).
    pub spp: u32,
    /// Adaptive anti-aliasing; `None`: `spp` samples in every pixel.
    pub adaptive: Option<AdaptiveSamples>,
    /// Pixel filter.
    pub filter: PixelFilter,
    /// Seed of every random decision.
    pub seed: u64,
    /// Maximum trace depth: the most surface interactions a light path may have between the
    /// light and the camera. Vertices up to it are lit and trace on, the next one only adds
    /// its emission (1 = direct light only: a mirror's rays are still traced, within
    /// `reflection_depth`, and see emitters but no lit surfaces).
    pub max_depth: u32,
    /// Most glossy or mirror reflections along one path.
    pub reflection_depth: u32,
    /// Most refractions (or transparency pass-throughs) along one path.
    pub refraction_depth: u32,
    /// Radiance integrator of the `shade` stage.
    pub integrator: Integrator,
    /// Face visibility.
    pub face: Face,
    /// BVH build quality.
    pub bvh_quality: BvhQuality,
    /// Light samples per shading point for emitting meshes (rectangular lights carry their
    /// own count).
    pub light_samples: u32,
    /// Photon maps to build (`trace_photons`) and use in the `Direct` integrator.
    pub photons: PhotonSettings,
    /// A file the photon maps are loaded from when its content hash matches, and written to
    /// otherwise (mental ray `photonmap file`); `None`: maps live only in memory.
    pub photon_map: Option<PhotonMapFile>,
    /// Features switched off for this run (`options.disable`, `--disable`).
    pub disabled: crate::features::Features,
    /// Diagnostic view replacing the beauty pass (`options.diagnostic`, `--diagnostic`).
    pub diagnostic: Option<crate::diagnostic::Diagnostic>,
}

/// `options: (photon_map: (file: "scene.pmap", rebuild: false))`: where photon maps persist
/// between runs (format and hash in `photon::file` and `photon::key`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PhotonMapFile {
    /// The file, as written (relative paths resolve against the working directory).
    pub path: std::path::PathBuf,
    /// Trace the maps and rewrite the file even when its hash matches.
    pub rebuild: bool,
}

/// Accuracy knobs of one photon map.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhotonMapSettings {
    /// Photons emitted from the lights (the number stored differs: photons that miss the
    /// scene store nothing, bouncing photons store several).
    pub photons: u32,
    /// Largest gather radius in world units; 0 = automatic (2 % of the scene's bounding-box
    /// diagonal).
    pub radius: f32,
    /// Nearest photons per radiance estimate (k of the k-nearest-neighbour estimate), ≥ 2.
    pub gather: u32,
    /// Final-gather rays per shading point (global illumination only; ignored for caustics).
    pub final_gather: u32,
    /// Global illumination only: final-gather rays read irradiance at every fourth photon
    /// (`photon::irradiance`, computed on first use) on Lambertian surfaces; `false` runs the
    /// `gather`-photon estimate for every ray.
    pub precompute: bool,
    /// Caustic map only: emit photons only toward the caustic casters' bounding spheres
    /// (aimed emission, same expected value, far more photons stored); `false` emits in
    /// every direction the lights send light.
    pub aim: bool,
    /// Weighting of photons in an estimate (mental ray `caustic filter`).
    pub filter: PhotonFilter,
    /// Progressive photon mapping (`None`: one pass, k-nearest estimates).
    pub progressive: Option<ProgressiveSettings>,
}

/// Progressive photon mapping of one map (Hachisuka et al.): `passes` photon passes of
/// `photons` each, the gather radius of every shading point shrinking pass by pass.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProgressiveSettings {
    /// Photon passes, ≥ 1.
    pub passes: u32,
    /// Fraction of each pass's new photons kept (0 < α ≤ 1; 1 = no shrinking).
    pub alpha: f32,
}

/// How photons are weighted inside the gather disc of an estimate (mental ray `caustic
/// filter`); the weights live in `photon::filter`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PhotonFilter {
    /// Every photon weighs 1.
    Box,
    /// Weight falling linearly to `1 − 1/k` at the disc's edge; `k ≥ 1` (1: to zero).
    Cone {
        /// Jensen's `k`, ≥ 1.
        k: f32,
    },
    /// Gaussian weight (Pavicic's normalised form).
    Gauss,
}

/// Which photon maps a render builds; `None` = off (the default for both).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PhotonSettings {
    /// Caustic map: photons stored at diffuse surfaces after one or more specular bounces.
    pub caustics: Option<PhotonMapSettings>,
    /// Global illumination map: photons stored at every diffuse hit, used through final
    /// gathering for indirect diffuse light.
    pub global_illumination: Option<PhotonMapSettings>,
    /// Most reflections and refractions of one photon (mental ray `photon trace depth`),
    /// default unlimited.
    pub depth: PhotonDepth,
}

/// Most scattering events of one photon (mental ray `photon trace depth r t s`): a photon
/// that has been reflected `reflection` times (diffuse, glossy or mirror), transmitted
/// `refraction` times (refraction or pass-through), or scattered `sum` times in all, scatters
/// no further (its power is counted as truncated). Deposits are not limited: the last hit
/// still stores its photon.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PhotonDepth {
    /// Most reflections.
    pub reflection: u32,
    /// Most transmissions.
    pub refraction: u32,
    /// Most scattering events of either kind.
    pub sum: u32,
}

impl PhotonDepth {
    /// No limit (photons end by Russian roulette, escape or the tracer's bounce cap).
    pub const UNLIMITED: Self = Self {
        reflection: u32::MAX,
        refraction: u32::MAX,
        sum: u32::MAX,
    };
}

impl Default for PhotonDepth {
    fn default() -> Self {
        Self::UNLIMITED
    }
}

impl PhotonSettings {
    /// Whether any photon map is requested.
    pub fn any(&self) -> bool {
        self.caustics.is_some() || self.global_illumination.is_some()
    }
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            spp: 4,
            adaptive: None,
            filter: PixelFilter::Box,
            seed: 0,
            max_depth: 4,
            reflection_depth: 4,
            refraction_depth: 4,
            integrator: Integrator::Direct,
            face: Face::Front,
            bvh_quality: BvhQuality::Medium,
            light_samples: 16,
            photons: PhotonSettings::default(),
            photon_map: None,
            disabled: crate::features::Features::NONE,
            diagnostic: None,
        }
    }
}

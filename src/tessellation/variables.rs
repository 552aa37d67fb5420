//! User texture coordinates and normals (RenderMan's `s`, `t`, `N` primitive variables) on
//! patch meshes and NURBS: a patch source whose samples take `uv` and `n` from the
//! [`SurfaceVariables`] instead of the surface's own parameters and geometric normal.
//!
//! `Control` values are evaluated by a twin of the surface whose control points are the
//! values (the same basis, knots and weights); `Corners` values bilinearly from the four
//! values of the patch's block (its index among RenderMan's uniform values).

use glam::{DVec3, Vec3, Vec4};

use super::nurbs::NurbsSource;
use super::patch::PatchMeshSource;
use super::{GeometryError, PatchSource, SurfaceSample};
use crate::components::{NurbsSurface, PatchMesh, SurfaceValues, SurfaceVariables};

/// How one variable is evaluated.
enum Channel<'a> {
    /// A twin surface: its position is the value.
    Twin(Box<dyn PatchSource + 'a>),
    /// Four values per block.
    Corners(&'a [Vec3]),
}

impl Channel<'_> {
    fn at(&self, patch: usize, block: usize, u: f64, v: f64) -> DVec3 {
        match self {
            Channel::Twin(t) => t.eval(patch, u, v).p,
            Channel::Corners(c) => {
                let q = &c[4 * block..4 * block + 4];
                let w = [(1.0 - u) * (1.0 - v), u * (1.0 - v), (1.0 - u) * v, u * v];
                (0..4).map(|k| q[k].as_dvec3() * w[k]).sum()
            }
        }
    }
}

/// A patch source with user `s`, `t` and normals.
pub struct Varied<'a> {
    src: &'a dyn PatchSource,
    /// The block (uniform value index) of each patch.
    blocks: Vec<usize>,
    s: Option<Channel<'a>>,
    t: Option<Channel<'a>>,
    normals: Option<Channel<'a>>,
}

/// Checks the value counts of `vars`: `control` per control point, four per block.
pub fn check(
    vars: &SurfaceVariables,
    control: usize,
    blocks: usize,
    what: &str,
) -> Result<(), GeometryError> {
    for (name, v) in [("s", &vars.s), ("t", &vars.t), ("normals", &vars.normals)] {
        let Some(v) = v else { continue };
        let (want, per) = match v {
            SurfaceValues::Control(_) => (control, "one per control point"),
            SurfaceValues::Corners(_) => (blocks, "one per patch or face corner"),
        };
        if v.values().len() != want {
            return Err(GeometryError::BadCount {
                message: format!(
                    "{what}: {name}: expected {want} values ({per}), found {}",
                    v.values().len()
                ),
            });
        }
        if v.values().iter().any(|x| !x.is_finite()) {
            return Err(GeometryError::NotFinite { parameter: "vars" });
        }
    }
    Ok(())
}

impl<'a> Varied<'a> {
    fn new(
        src: &'a dyn PatchSource,
        blocks: Vec<usize>,
        vars: &'a SurfaceVariables,
        twin: impl Fn(&'a [Vec3]) -> Result<Box<dyn PatchSource + 'a>, GeometryError>,
    ) -> Result<Self, GeometryError> {
        let channel = |v: &'a Option<SurfaceValues>| -> Result<Option<Channel<'a>>, GeometryError> {
            Ok(match v {
                None => None,
                Some(SurfaceValues::Control(c)) => Some(Channel::Twin(twin(c)?)),
                Some(SurfaceValues::Corners(c)) => Some(Channel::Corners(c)),
            })
        };
        Ok(Self {
            src,
            blocks,
            s: channel(&vars.s)?,
            t: channel(&vars.t)?,
            normals: channel(&vars.normals)?,
        })
    }

    /// A patch mesh `src` (built from `mesh`) with `mesh.vars`.
    pub fn patches(src: &'a PatchMeshSource, mesh: &'a PatchMesh) -> Result<Self, GeometryError> {
        let blocks = (0..src.patch_count()).collect();
        check(
            &mesh.vars,
            mesh.points.len(),
            4 * src.patch_count(),
            "patch mesh",
        )?;
        Self::new(src, blocks, &mesh.vars, |values| {
            let twin = PatchMesh {
                points: values.to_vec(),
                vars: SurfaceVariables::default(),
                ..mesh.clone()
            };
            Ok(Box::new(PatchMeshSource::new(&twin)?))
        })
    }

    /// A NURBS `src` (built from `surface`) with `surface.vars`.
    pub fn nurbs(src: &'a NurbsSource, surface: &'a NurbsSurface) -> Result<Self, GeometryError> {
        let blocks = (0..src.patch_count()).map(|p| src.segment(p)).collect();
        check(
            &surface.vars,
            surface.points.len(),
            4 * NurbsSource::segments(surface),
            "nurbs",
        )?;
        Self::new(src, blocks, &surface.vars, |values| {
            let twin = NurbsSurface {
                points: values
                    .iter()
                    .zip(&surface.points)
                    .map(|(v, p)| Vec4::new(v.x, v.y, v.z, p.w))
                    .collect(),
                vars: SurfaceVariables::default(),
                ..surface.clone()
            };
            Ok(Box::new(NurbsSource::new(&twin)?))
        })
    }
}

impl PatchSource for Varied<'_> {
    fn patch_count(&self) -> usize {
        self.src.patch_count()
    }
    fn corner_count(&self) -> usize {
        self.src.corner_count()
    }
    fn corners(&self, patch: usize) -> [u32; 4] {
        self.src.corners(patch)
    }
    fn eval(&self, patch: usize, u: f64, v: f64) -> SurfaceSample {
        let mut sample = self.src.eval(patch, u, v);
        let block = self.blocks[patch];
        if let Some(c) = &self.s {
            sample.uv.x = c.at(patch, block, u, v).x;
        }
        if let Some(c) = &self.t {
            sample.uv.y = c.at(patch, block, u, v).x;
        }
        if let Some(c) = &self.normals {
            if let Some(n) = c.at(patch, block, u, v).try_normalize() {
                sample.n = n;
            }
        }
        sample
    }
    fn grid(&self) -> (usize, usize) {
        self.src.grid()
    }
}

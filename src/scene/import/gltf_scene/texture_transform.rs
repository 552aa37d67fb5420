//! `KHR_texture_transform` on a material's texture reference → the `uv` input of the
//! `Image`/`Alpha` nodes that read it. The extension maps the file's texture coordinates by
//! `T(offset) · R(rotation) · S(scale)`:
//!
//! ```text
//! u' = offset.x + cos r · scale.x · u + sin r · scale.y · v
//! v' = offset.y − sin r · scale.x · u + cos r · scale.y · v
//! ```
//!
//! in glTF's coordinates (`v` down). The reader flips `v` (`V = 1 − v`, see
//! `mesh_files/gltf_file.rs`), so the node computes the same map in the flipped coordinates:
//! `u' = (offset.x + sin r · scale.y) + cos r · scale.x · u − sin r · scale.y · V` and
//! `V' = (1 − offset.y − cos r · scale.y) + sin r · scale.x · u + cos r · scale.y · V`, as
//! `Combine(Add(…, Mul(…, Channel(Uv, 0))), …, 0)`. Its `texCoord` replaces the texture
//! reference's.

use serde_json::Value;

use crate::scene::desc::{InputDesc, NodeDesc};

/// A texture reference's `KHR_texture_transform`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UvTransform {
    /// `offset` (default 0, 0).
    pub offset: [f64; 2],
    /// `rotation`, radians counter-clockwise (default 0).
    pub rotation: f64,
    /// `scale` (default 1, 1).
    pub scale: [f64; 2],
    /// `texCoord`, which overrides the reference's own.
    pub tex_coord: Option<u32>,
}

/// A member of the extension that is not what it allows: (key, what it must be), as
/// `("scale", "two finite numbers")`.
pub type Malformed = (&'static str, &'static str);

/// Reads the extension's object (the normal texture's: the `gltf` crate reads it only on
/// other texture references); the error names the member that is malformed.
pub fn parse(v: &Value) -> Result<UvTransform, Malformed> {
    let pair = |key: &'static str, default: [f64; 2]| -> Result<[f64; 2], _> {
        let Some(v) = v.get(key) else {
            return Ok(default);
        };
        v.as_array()
            .filter(|a| a.len() == 2)
            .and_then(|a| Some([a[0].as_f64()?, a[1].as_f64()?]))
            .filter(|p| p.iter().all(|x| x.is_finite()))
            .ok_or((key, "two finite numbers"))
    };
    let rotation = match v.get("rotation") {
        None => 0.0,
        Some(r) => r
            .as_f64()
            .filter(|r| r.is_finite())
            .ok_or(("rotation", "a finite number (radians)"))?,
    };
    let tex_coord = match v.get("texCoord") {
        None => None,
        Some(t) => Some(
            t.as_u64()
                .and_then(|t| u32::try_from(t).ok())
                .ok_or(("texCoord", "a non-negative integer"))?,
        ),
    };
    Ok(UvTransform {
        offset: pair("offset", [0.0, 0.0])?,
        rotation,
        scale: pair("scale", [1.0, 1.0])?,
        tex_coord,
    })
}

impl UvTransform {
    /// The map in stagelight's texture coordinates, `(u', V') = c + M · (u, V)`: rows
    /// `[c, m_u, m_V]`.
    pub fn rows(&self) -> [[f64; 3]; 2] {
        let (s, c) = self.rotation.sin_cos();
        let [ox, oy] = self.offset;
        let [sx, sy] = self.scale;
        [
            [ox + s * sy, c * sx, -s * sy],
            [1.0 - oy - c * sy, s * sx, c * sy],
        ]
    }

    /// The `uv` node of an image read through this transform.
    pub fn uv_node(&self) -> InputDesc {
        let node = |n: NodeDesc| InputDesc::Node(Box::new(n));
        let uv = || node(NodeDesc::Uv);
        let row = |[k, a, b]: [f64; 3]| {
            let mut sum: Option<InputDesc> = (k != 0.0).then_some(InputDesc::Number(k));
            for (coefficient, channel) in [(a, 0), (b, 1)] {
                if coefficient == 0.0 {
                    continue;
                }
                let read = node(NodeDesc::Channel(uv(), channel));
                let term = if coefficient == 1.0 {
                    read
                } else {
                    node(NodeDesc::Mul(InputDesc::Number(coefficient), read))
                };
                sum = Some(match sum {
                    Some(s) => node(NodeDesc::Add(s, term)),
                    None => term,
                });
            }
            sum.unwrap_or(InputDesc::Number(0.0))
        };
        let [first, second] = self.rows();
        node(NodeDesc::Combine(
            row(first),
            row(second),
            InputDesc::Number(0.0),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The extension's map in glTF's coordinates, written as its specification does.
    fn gltf_map(t: &UvTransform, u: f64, v: f64) -> (f64, f64) {
        let (s, c) = t.rotation.sin_cos();
        (
            t.offset[0] + c * t.scale[0] * u + s * t.scale[1] * v,
            t.offset[1] - s * t.scale[0] * u + c * t.scale[1] * v,
        )
    }

    #[test]
    fn the_rows_are_the_extensions_map_with_v_flipped() {
        let t = UvTransform {
            offset: [0.25, -0.5],
            rotation: 0.7,
            scale: [2.0, 3.0],
            tex_coord: None,
        };
        let [a, b] = t.rows();
        for (u, v) in [(0.0, 0.0), (1.0, 0.0), (0.3, 0.8), (-2.0, 5.0)] {
            let (gu, gv) = gltf_map(&t, u, v);
            let big_v = 1.0 - v;
            let got_u = a[0] + a[1] * u + a[2] * big_v;
            let got_v = b[0] + b[1] * u + b[2] * big_v;
            assert!((got_u - gu).abs() < 1e-12 && (got_v - (1.0 - gv)).abs() < 1e-12);
        }
    }

    #[test]
    fn the_identity_reads_plain_uvs_and_bad_members_are_named() {
        let t = parse(&serde_json::json!({})).unwrap();
        assert_eq!(t.rows(), [[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]);
        let t = parse(&serde_json::json!({"texCoord": 1, "offset": [0.5, 0]})).unwrap();
        assert_eq!((t.tex_coord, t.offset), (Some(1), [0.5, 0.0]));
        assert_eq!(
            parse(&serde_json::json!({"scale": [1, "x"]})),
            Err(("scale", "two finite numbers"))
        );
        assert_eq!(
            parse(&serde_json::json!({"rotation": "1"})),
            Err(("rotation", "a finite number (radians)"))
        );
    }
}

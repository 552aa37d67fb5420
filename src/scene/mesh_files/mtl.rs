//! Wavefront MTL reader: the material library an OBJ file names with `mtllib`, as a list of
//! [`MtlMaterial`]s read from bytes, or a located [`MeshFileError`].
//!
//! Read: `newmtl name`, the colours `Kd`, `Ks`, `Ke` (`r g b`, or one number for grey),
//! `Ns` (specular exponent, ≥ 0), `Ni` (index of refraction, > 0), `d` (opacity in \[0, 1\],
//! `-halo` accepted and ignored) and `Tr` (transparency, `d = 1 − Tr`), `illum` (0 to 10),
//! and the maps `map_Kd` and `map_Bump` / `bump` (options `-bm` and `-clamp` read, the
//! other standard options accepted and skipped). `Ka`, `Tf`, `sharpness`, the other maps
//! and the PBR extension statements are valid and ignored. Everything else — a statement
//! that is not MTL, a value that is not a number or out of range, a property before the
//! first `newmtl`, a material defined twice — is an error at its line and column.
//!
//! How the materials become scene materials is [`crate::scene::obj_materials`]'s job.

use super::obj::{numbers, words};
use super::{column, shown, MeshFileError};

/// Valid MTL statements this reader does not use.
const IGNORED: &[&[u8]] = &[
    b"Ka",
    b"Tf",
    b"sharpness",
    b"map_Ka",
    b"map_Ks",
    b"map_Ke",
    b"map_Ns",
    b"map_d",
    b"map_Tr",
    b"map_aat",
    b"disp",
    b"decal",
    b"refl",
    b"norm",
    b"Pr",
    b"Pm",
    b"Ps",
    b"Pc",
    b"Pcr",
    b"aniso",
    b"anisor",
    b"map_Pr",
    b"map_Pm",
    b"map_Ps",
    b"map_Disp",
];

/// A texture a map statement names.
#[derive(Debug, Clone, PartialEq)]
pub struct MapRef {
    /// The file as written (relative to the MTL file).
    pub file: String,
    /// `-clamp on`: clamp instead of repeat.
    pub clamp: bool,
    /// `-bm x`: bump multiplier, default 1.
    pub bump_multiplier: f64,
    /// 1-based line of the map statement.
    pub line: usize,
    /// 1-based column of the file name.
    pub column: usize,
}

/// One `newmtl` block.
#[derive(Debug, Clone, PartialEq)]
pub struct MtlMaterial {
    /// The material's name.
    pub name: String,
    /// Diffuse colour `Kd`.
    pub diffuse: Option<[f64; 3]>,
    /// Specular colour `Ks`.
    pub specular: Option<[f64; 3]>,
    /// Emitted colour `Ke`.
    pub emission: Option<[f64; 3]>,
    /// Specular exponent `Ns`.
    pub exponent: Option<f64>,
    /// Index of refraction `Ni`.
    pub ior: Option<f64>,
    /// Opacity `d` (or `1 − Tr`), the last written.
    pub opacity: Option<f64>,
    /// Illumination model `illum`.
    pub illum: Option<u32>,
    /// Diffuse texture `map_Kd`.
    pub diffuse_map: Option<MapRef>,
    /// Bump (height) texture `map_Bump` / `bump`.
    pub bump_map: Option<MapRef>,
}

impl MtlMaterial {
    fn new(name: String) -> Self {
        Self {
            name,
            diffuse: None,
            specular: None,
            emission: None,
            exponent: None,
            ior: None,
            opacity: None,
            illum: None,
            diffuse_map: None,
            bump_map: None,
        }
    }
}

/// An error inside a line: byte offset in the line and message.
type LineError = (usize, String);

/// Parses an MTL file (see the module documentation for what is read).
pub fn parse(bytes: &[u8]) -> Result<Vec<MtlMaterial>, MeshFileError> {
    let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
    let mut materials: Vec<MtlMaterial> = Vec::new();
    for (k, line) in bytes.split(|&b| b == b'\n').enumerate() {
        let line = line.strip_suffix(b"\r").unwrap_or(line);
        statement(&mut materials, line, k + 1).map_err(|(offset, message)| {
            MeshFileError::at_line(k + 1, column(line, offset), message)
        })?;
    }
    Ok(materials)
}

fn statement(
    materials: &mut Vec<MtlMaterial>,
    line: &[u8],
    number: usize,
) -> Result<(), LineError> {
    let words = words(line);
    let Some(&(at, keyword)) = words.first() else {
        return Ok(());
    };
    let args = &words[1..];
    if keyword.starts_with(b"#") {
        return Ok(());
    }
    if keyword == b"newmtl" {
        let start = at + keyword.len();
        let Some(&(name_at, _)) = args.first() else {
            return Err((start, "newmtl needs a material name".into()));
        };
        let name = std::str::from_utf8(&line[name_at..])
            .map_err(|e| {
                (
                    name_at + e.valid_up_to(),
                    "the material name is not UTF-8".into(),
                )
            })?
            .trim_end()
            .to_string();
        if materials.iter().any(|m| m.name == name) {
            return Err((
                name_at,
                format!(
                    "material \"{}\" is defined twice in this file",
                    shown(name.as_bytes())
                ),
            ));
        }
        materials.push(MtlMaterial::new(name));
        return Ok(());
    }
    let known = matches!(
        keyword,
        b"Kd"
            | b"Ks"
            | b"Ke"
            | b"Ns"
            | b"Ni"
            | b"d"
            | b"Tr"
            | b"illum"
            | b"map_Kd"
            | b"map_Bump"
            | b"map_bump"
            | b"bump"
    ) || IGNORED.contains(&keyword);
    if !known {
        return Err((
            at,
            format!("\"{}\" is not an MTL statement", shown(keyword)),
        ));
    }
    let Some(m) = materials.last_mut() else {
        return Err((
            at,
            format!(
                "\"{}\" comes before any \"newmtl\": start a material with newmtl name",
                shown(keyword)
            ),
        ));
    };
    match keyword {
        b"Kd" => m.diffuse = Some(colour(args, at, "Kd")?),
        b"Ks" => m.specular = Some(colour(args, at, "Ks")?),
        b"Ke" => m.emission = Some(colour(args, at, "Ke")?),
        b"Ns" => m.exponent = Some(scalar(args, at, "Ns", 0.0..=f64::MAX, "≥ 0")?),
        b"Ni" => {
            let x = scalar(args, at, "Ni", f64::MIN_POSITIVE..=f64::MAX, "> 0")?;
            m.ior = Some(x);
        }
        b"d" => {
            let args = match args.first() {
                Some((_, b"-halo")) => &args[1..],
                _ => args,
            };
            m.opacity = Some(scalar(args, at, "d", 0.0..=1.0, "in [0, 1]")?);
        }
        b"Tr" => m.opacity = Some(1.0 - scalar(args, at, "Tr", 0.0..=1.0, "in [0, 1]")?),
        b"illum" => {
            let x = scalar(args, at, "illum", 0.0..=10.0, "a whole number from 0 to 10")?;
            if x.fract() != 0.0 {
                return Err((
                    args[0].0,
                    "illum must be a whole number from 0 to 10".into(),
                ));
            }
            m.illum = Some(x as u32);
        }
        b"map_Kd" => m.diffuse_map = Some(map(line, number, args, at, keyword)?),
        b"map_Bump" | b"map_bump" | b"bump" => {
            m.bump_map = Some(map(line, number, args, at, keyword)?)
        }
        _ => {}
    }
    Ok(())
}

/// `r g b` or one grey value, each finite and ≥ 0.
fn colour(args: &[(usize, &[u8])], at: usize, keyword: &str) -> Result<[f64; 3], LineError> {
    if let Some(&(offset, word @ (b"spectral" | b"xyz"))) = args.first() {
        return Err((
            offset,
            format!(
                "{keyword} {} colours are not supported: write {keyword} r g b",
                shown(word)
            ),
        ));
    }
    let need = format!("{keyword} needs 1 or 3 numbers (\"{keyword} r g b\")");
    let n = numbers(args, at, 1..=3, &need)?;
    if n.len() == 2 {
        return Err((args[1].0, format!("{need}, found 2")));
    }
    for (k, x) in n.iter().enumerate() {
        if !x.is_finite() || *x < 0.0 {
            return Err((
                args[k].0,
                format!("{keyword} values must be finite and ≥ 0, found {x}"),
            ));
        }
    }
    Ok(if n.len() == 1 {
        [n[0]; 3]
    } else {
        [n[0], n[1], n[2]]
    })
}

/// One number in `range` (`what` says the range in words).
fn scalar(
    args: &[(usize, &[u8])],
    at: usize,
    keyword: &str,
    range: std::ops::RangeInclusive<f64>,
    what: &str,
) -> Result<f64, LineError> {
    let n = numbers(args, at, 1..=1, &format!("{keyword} needs 1 number"))?;
    if !range.contains(&n[0]) {
        return Err((
            args[0].0,
            format!("{keyword} must be {what}, found {}", n[0]),
        ));
    }
    Ok(n[0])
}

/// Options (`-name value…`) then the file name, which is the rest of the line.
fn map(
    line: &[u8],
    number: usize,
    args: &[(usize, &[u8])],
    at: usize,
    keyword: &[u8],
) -> Result<MapRef, LineError> {
    let mut out = MapRef {
        file: String::new(),
        clamp: false,
        bump_multiplier: 1.0,
        line: number,
        column: 1,
    };
    let mut k = 0;
    let number = |k: usize| -> Option<f64> {
        args.get(k)
            .and_then(|(_, w)| std::str::from_utf8(w).ok())
            .and_then(|s| s.parse::<f64>().ok())
    };
    while let Some(&(offset, option)) = args.get(k) {
        if !option.starts_with(b"-") || number(k).is_some() {
            break;
        }
        let missing = || {
            (
                offset,
                format!("the option {} needs a value", shown(option)),
            )
        };
        match option {
            b"-blendu" | b"-blendv" | b"-cc" | b"-clamp" => {
                let (_, value) = *args.get(k + 1).ok_or_else(missing)?;
                let on = match value {
                    b"on" => true,
                    b"off" => false,
                    _ => {
                        return Err((
                            args[k + 1].0,
                            format!(
                                "the option {} takes on or off, found \"{}\"",
                                shown(option),
                                shown(value)
                            ),
                        ))
                    }
                };
                if option == b"-clamp" {
                    out.clamp = on;
                }
                k += 2;
            }
            b"-bm" | b"-boost" | b"-texres" => {
                let x = number(k + 1).ok_or_else(missing)?;
                if option == b"-bm" {
                    if !x.is_finite() {
                        return Err((args[k + 1].0, "-bm must be finite".into()));
                    }
                    out.bump_multiplier = x;
                }
                k += 2;
            }
            b"-mm" => {
                if number(k + 1).is_none() || number(k + 2).is_none() {
                    return Err((offset, "the option -mm needs 2 numbers".into()));
                }
                k += 3;
            }
            b"-o" | b"-s" | b"-t" => {
                k += 1;
                let first = k;
                while k < first + 3 && number(k).is_some() {
                    k += 1;
                }
                if k == first {
                    return Err(missing());
                }
            }
            b"-imfchan" | b"-type" => {
                args.get(k + 1).ok_or_else(missing)?;
                k += 2;
            }
            _ => {
                return Err((
                    offset,
                    format!("\"{}\" is not a texture map option", shown(option)),
                ))
            }
        }
    }
    let Some(&(start, _)) = args.get(k) else {
        return Err((
            at + keyword.len(),
            format!("{} needs a file name", shown(keyword)),
        ));
    };
    out.column = column(line, start);
    out.file = std::str::from_utf8(&line[start..])
        .map_err(|e| (start + e.valid_up_to(), "the file name is not UTF-8".into()))?
        .trim_end()
        .to_string();
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::mesh_files::Location;

    fn error(bytes: &[u8]) -> (usize, usize, String) {
        match parse(bytes) {
            Err(MeshFileError::Parse {
                at: Location::Text { line, column },
                message,
            }) => (line, column, message),
            other => panic!("expected a parse error, got {other:?}"),
        }
    }

    #[test]
    fn reads_every_mapped_statement() {
        let mtl = b"# made by hand\nnewmtl red paint\nKd 0.8 0.1 0.1\nKs 0.5\nNs 40\nNi 1.45\n\
                    Tr 0.25\nKe 0 0 2\nillum 2\nKa 1 1 1\nmap_Kd -clamp on -o 0.5 0.5 tex/red wood.png\n\
                    bump -bm 0.02 h.png\nnewmtl plain\nd -halo 0.5\n";
        let m = parse(mtl).unwrap();
        assert_eq!(m.len(), 2);
        let red = &m[0];
        assert_eq!(red.name, "red paint");
        assert_eq!(red.diffuse, Some([0.8, 0.1, 0.1]));
        assert_eq!(red.specular, Some([0.5; 3]));
        assert_eq!(red.emission, Some([0.0, 0.0, 2.0]));
        assert_eq!((red.exponent, red.ior), (Some(40.0), Some(1.45)));
        assert_eq!((red.opacity, red.illum), (Some(0.75), Some(2)));
        let map = red.diffuse_map.as_ref().unwrap();
        assert_eq!((map.file.as_str(), map.clamp), ("tex/red wood.png", true));
        assert_eq!((map.line, map.column), (11, 29));
        let bump = red.bump_map.as_ref().unwrap();
        assert_eq!((bump.file.as_str(), bump.bump_multiplier), ("h.png", 0.02));
        assert_eq!(m[1].opacity, Some(0.5));
        assert_eq!(m[1].diffuse, None);
    }

    #[test]
    fn malformed_files_are_located() {
        assert_eq!(
            error(b"Kd 1 1 1\n"),
            (
                1,
                1,
                "\"Kd\" comes before any \"newmtl\": start a material with newmtl name".into()
            )
        );
        assert_eq!(
            error(b"newmtl a\nKd 1 x 1\n"),
            (2, 6, "\"x\" is not a number".into())
        );
        assert_eq!(
            error(b"newmtl a\nKd 1 1\n"),
            (
                2,
                6,
                "Kd needs 1 or 3 numbers (\"Kd r g b\"), found 2".into()
            )
        );
        assert_eq!(
            error(b"newmtl a\n  d 1.5\n"),
            (2, 5, "d must be in [0, 1], found 1.5".into())
        );
        assert_eq!(
            error(b"newmtl a\nKs -1 0 0\n"),
            (2, 4, "Ks values must be finite and ≥ 0, found -1".into())
        );
        assert_eq!(
            error(b"newmtl a\nmap_Kd -zz 1 t.png\n"),
            (2, 8, "\"-zz\" is not a texture map option".into())
        );
        assert_eq!(
            error(b"newmtl a\nmap_Kd -clamp\n"),
            (2, 8, "the option -clamp needs a value".into())
        );
        assert_eq!(
            error(b"newmtl a\nbump\n"),
            (2, 5, "bump needs a file name".into())
        );
        assert_eq!(
            error(b"newmtl a\nnewmtl a\n"),
            (2, 8, "material \"a\" is defined twice in this file".into())
        );
        assert_eq!(
            error(b"newmtl a\nillum 2.5\n"),
            (2, 7, "illum must be a whole number from 0 to 10".into())
        );
        assert_eq!(
            error(b"v 0 0 0\n"),
            (1, 1, "\"v\" is not an MTL statement".into())
        );
        assert_eq!(
            error(b"newmtl\n"),
            (1, 7, "newmtl needs a material name".into())
        );
    }

    #[test]
    fn an_empty_file_has_no_materials() {
        assert_eq!(parse(b"").unwrap(), vec![]);
        assert_eq!(parse(b"# nothing\r\n\r\n").unwrap(), vec![]);
    }
}

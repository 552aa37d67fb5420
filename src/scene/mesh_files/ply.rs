//! PLY (Stanford polygon file) reader: the `vertex` and `face` elements of an ASCII or
//! binary (little- or big-endian) PLY file as a [`MeshData`], read from bytes.
//!
//! What is read: positions `x y z` (any scalar type, kept in f64; ASCII values keep the
//! precision they are written with), normals `nx ny nz` (all three or none), texture
//! coordinates from the first complete pair of `s t`, `u v`, `texture_u texture_v` or
//! `texture_s texture_t`, and faces from the integer list `vertex_indices` (or
//! `vertex_index`), fan-triangulated like OBJ polygons, and vertex colours `red green blue`
//! (all three or none): integer colours are display values (divided by the type's
//! maximum, `uchar` 255, then decoded from sRGB to linear), floating-point colours are
//! linear as written. An `alpha` property and every other property or element are read
//! past and ignored. ASCII data holds one element per line, its values separated by white
//! space; blank lines (empty or white space only) between elements are skipped.
//!
//! A vertex position that is not a finite number (`nan`, `inf`) or lies beyond the f32
//! range is an error at its value. Errors are located: header problems and ASCII data at
//! line and column, binary data at its byte offset. The header's counts are checked against the size of the data before
//! anything is allocated for them, so a header cannot make the reader reserve more than
//! the file could hold; the data must hold exactly the elements the header declares.

use glam::{DVec3, Vec2, Vec3};

use super::{column, shown, Location, MeshData, MeshFileError};

/// A PLY scalar type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

/// Type names, with the sized aliases, as the header writes them.
const TYPES: [(&[u8], Scalar); 16] = [
    (b"char", Scalar::I8),
    (b"uchar", Scalar::U8),
    (b"short", Scalar::I16),
    (b"ushort", Scalar::U16),
    (b"int", Scalar::I32),
    (b"uint", Scalar::U32),
    (b"float", Scalar::F32),
    (b"double", Scalar::F64),
    (b"int8", Scalar::I8),
    (b"uint8", Scalar::U8),
    (b"int16", Scalar::I16),
    (b"uint16", Scalar::U16),
    (b"int32", Scalar::I32),
    (b"uint32", Scalar::U32),
    (b"float32", Scalar::F32),
    (b"float64", Scalar::F64),
];

impl Scalar {
    fn parse(word: &[u8]) -> Option<Scalar> {
        TYPES
            .iter()
            .find(|(name, _)| *name == word)
            .map(|&(_, s)| s)
    }

    fn name(self) -> &'static str {
        let (name, _) = TYPES
            .iter()
            .find(|(_, s)| *s == self)
            .expect("every type has a name");
        std::str::from_utf8(name).expect("type names are ASCII")
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_integer(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    /// The range of an integer type.
    fn range(self) -> (i64, i64) {
        match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => (i64::MIN, i64::MAX),
        }
    }
}

/// A value as read: integers exactly, floating-point values in f64.
#[derive(Debug, Clone, Copy)]
enum Num {
    Int(i64),
    Float(f64),
}

impl Num {
    fn as_f64(self) -> f64 {
        match self {
            Num::Int(i) => i as f64,
            Num::Float(x) => x,
        }
    }
}

/// A property's type.
#[derive(Debug, Clone, Copy)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

#[derive(Debug)]
struct Property {
    name: Vec<u8>,
    kind: Kind,
    /// Header line.
    line: usize,
}

#[derive(Debug)]
struct Element {
    name: Vec<u8>,
    count: usize,
    /// Header line and column of the count.
    line: usize,
    count_column: usize,
    properties: Vec<Property>,
}

impl Element {
    fn property(&self, name: &[u8]) -> Option<usize> {
        self.properties.iter().position(|p| p.name == name)
    }

    /// The fewest bytes one element takes in the data.
    fn min_size(&self, ascii: bool) -> usize {
        self.properties
            .iter()
            .map(|p| match (ascii, p.kind) {
                // A value and the separator or newline after it.
                (true, _) => 2,
                (false, Kind::Scalar(s)) => s.size(),
                (false, Kind::List { count, .. }) => count.size(),
            })
            .sum()
    }

    /// `"3 vertices"`, `"1 face"`, `"2 \"edge\" elements"`.
    fn counted(&self, n: usize) -> String {
        match (self.name.as_slice(), n) {
            (b"vertex", 1) => "1 vertex".into(),
            (b"vertex", n) => format!("{n} vertices"),
            (b"face", 1) => "1 face".into(),
            (b"face", n) => format!("{n} faces"),
            (name, 1) => format!("1 \"{}\" element", shown(name)),
            (name, n) => format!("{n} \"{}\" elements", shown(name)),
        }
    }

    /// `vertex 3`, `"edge" element 3`.
    fn one(&self, i: usize) -> String {
        match self.name.as_slice() {
            b"vertex" | b"face" => format!("{} {i}", shown(&self.name)),
            name => format!("\"{}\" element {i}", shown(name)),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Binary { big_endian: bool },
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the data, and the line it starts on.
    data: usize,
    data_line: usize,
}

/// Parses a PLY file (see the module documentation).
pub fn parse(bytes: &[u8]) -> Result<MeshData, MeshFileError> {
    let header = header(bytes)?;
    let layout = Layout::of(&header)?;
    check_sizes(&header, bytes.len() - header.data)?;
    let data = &bytes[header.data..];
    match header.encoding {
        Encoding::Ascii => read(&header, &layout, Ascii::new(data, header.data_line)),
        Encoding::Binary { big_endian } => read(
            &header,
            &layout,
            Binary {
                data,
                start: header.data,
                pos: 0,
                last: 0,
                big_endian,
            },
        ),
    }
}

/// The words of a header line with their byte offsets.
fn words(line: &[u8]) -> Vec<(usize, &[u8])> {
    let mut out = Vec::new();
    let mut start = None;
    for (k, &b) in line.iter().chain(std::iter::once(&b' ')).enumerate() {
        match (b.is_ascii_whitespace(), start) {
            (false, None) => start = Some(k),
            (true, Some(s)) => {
                out.push((s, &line[s..k]));
                start = None;
            }
            _ => {}
        }
    }
    out
}

fn header(bytes: &[u8]) -> Result<Header, MeshFileError> {
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut offset = 0;
    let mut number = 0;
    let mut last = (1, 1);
    while offset < bytes.len() {
        number += 1;
        let end = bytes[offset..]
            .iter()
            .position(|&b| b == b'\n')
            .map_or(bytes.len(), |k| offset + k);
        let raw = &bytes[offset..end];
        let line = raw.strip_suffix(b"\r").unwrap_or(raw);
        offset = (end + 1).min(bytes.len());
        last = (number, column(line, line.len()));
        let err =
            |at: usize, message: String| MeshFileError::at_line(number, column(line, at), message);
        let w = words(line);
        if number == 1 {
            // Trailing blanks are allowed here as on every other header line.
            if line.trim_ascii_end() != b"ply" {
                return Err(err(0, "a PLY file starts with the line \"ply\"".into()));
            }
            continue;
        }
        let Some(&(at, keyword)) = w.first() else {
            return Err(err(0, "a PLY header has no empty lines".into()));
        };
        match keyword {
            b"comment" | b"obj_info" => {}
            b"format" => {
                if encoding.is_some() {
                    return Err(err(at, "the header has a second \"format\" line".into()));
                }
                encoding = Some(match w.get(1).map(|&(_, f)| f) {
                    Some(b"ascii") => Encoding::Ascii,
                    Some(b"binary_little_endian") => Encoding::Binary { big_endian: false },
                    Some(b"binary_big_endian") => Encoding::Binary { big_endian: true },
                    _ => {
                        let at = w.get(1).map_or(line.len(), |&(k, _)| k);
                        return Err(err(
                            at,
                            "the format is ascii, binary_little_endian or binary_big_endian".into(),
                        ));
                    }
                });
                match w.get(2) {
                    Some((_, b"1.0")) if w.len() == 3 => {}
                    Some(&(k, version)) if w.len() == 3 => {
                        return Err(err(
                            k,
                            format!("PLY version {} is not supported (only 1.0)", shown(version)),
                        ))
                    }
                    _ => return Err(err(at, "a format line is \"format ENCODING 1.0\"".into())),
                }
            }
            _ if encoding.is_none() => {
                return Err(err(
                    at,
                    "the second line of a PLY header is \"format ENCODING 1.0\"".into(),
                ))
            }
            b"element" => {
                let [_, (_, name), (count_at, count)] = w[..] else {
                    return Err(err(at, "an element line is \"element NAME COUNT\"".into()));
                };
                let count = std::str::from_utf8(count)
                    .ok()
                    .filter(|s| s.bytes().all(|b| b.is_ascii_digit()))
                    .and_then(|s| s.parse::<usize>().ok())
                    .ok_or_else(|| {
                        err(
                            count_at,
                            format!(
                                "\"{}\" is not an element count (a whole number)",
                                shown(count)
                            ),
                        )
                    })?;
                if elements.iter().any(|e| e.name == name) {
                    return Err(err(
                        at,
                        format!("the header has a second \"{}\" element", shown(name)),
                    ));
                }
                elements.push(Element {
                    name: name.to_vec(),
                    count,
                    line: number,
                    count_column: column(line, count_at),
                    properties: Vec::new(),
                });
            }
            b"property" => {
                let Some(element) = elements.last_mut() else {
                    return Err(err(
                        at,
                        "a property line must follow an element line".into(),
                    ));
                };
                let ty = |k: usize| -> Result<Scalar, MeshFileError> {
                    let (at, word) = w[k];
                    Scalar::parse(word).ok_or_else(|| {
                        err(
                            at,
                            format!(
                                "\"{}\" is not a PLY type: use char, uchar, short, ushort, int, \
                                 uint, float or double (or int8 … float64)",
                                shown(word)
                            ),
                        )
                    })
                };
                let (kind, name) = match w.get(1) {
                    Some((_, b"list")) if w.len() == 5 => {
                        let count = ty(2)?;
                        if !count.is_integer() {
                            return Err(err(
                                w[2].0,
                                format!(
                                    "a list's length has an integer type, not {}",
                                    count.name()
                                ),
                            ));
                        }
                        (
                            Kind::List {
                                count,
                                item: ty(3)?,
                            },
                            w[4].1,
                        )
                    }
                    Some((_, b"list")) => {
                        return Err(err(
                            at,
                            "a list property line is \"property list LENGTH_TYPE ITEM_TYPE NAME\""
                                .into(),
                        ))
                    }
                    Some(_) if w.len() == 3 => (Kind::Scalar(ty(1)?), w[2].1),
                    _ => return Err(err(at, "a property line is \"property TYPE NAME\"".into())),
                };
                if element.property(name).is_some() {
                    return Err(err(
                        w[w.len() - 1].0,
                        format!(
                            "element \"{}\" has a second \"{}\" property",
                            shown(&element.name),
                            shown(name)
                        ),
                    ));
                }
                element.properties.push(Property {
                    name: name.to_vec(),
                    kind,
                    line: number,
                });
            }
            b"end_header" if w.len() == 1 => {
                return Ok(Header {
                    encoding: encoding.expect("checked above"),
                    elements,
                    data: offset,
                    data_line: number + 1,
                });
            }
            _ => {
                return Err(err(
                    at,
                    format!(
                        "\"{}\" is not a PLY header line: expected element, property, comment, \
                         obj_info or end_header",
                        shown(keyword)
                    ),
                ))
            }
        }
    }
    let message = if bytes.is_empty() {
        "a PLY file starts with the line \"ply\""
    } else {
        "the header ends without an \"end_header\" line"
    };
    Err(MeshFileError::at_line(last.0, last.1, message))
}

/// Where the mesh's values are among the elements' properties.
struct Layout {
    vertex: usize,
    position: [usize; 3],
    normal: Option<[usize; 3]>,
    uv: Option<[usize; 2]>,
    /// The colour properties and, per channel, the divisor of integer types (`None`: a
    /// floating-point channel, linear as written).
    colour: Option<[(usize, Option<f64>); 3]>,
    /// The face element and its index list.
    face: Option<(usize, usize)>,
}

impl Layout {
    fn of(h: &Header) -> Result<Layout, MeshFileError> {
        let element = |name: &[u8]| h.elements.iter().position(|e| e.name == name);
        let at_element = |e: &Element, message: String| MeshFileError::at_line(e.line, 1, message);
        let Some(vertex) = element(b"vertex") else {
            return Err(MeshFileError::at_line(
                h.data_line - 1,
                1,
                "the header declares no \"vertex\" element",
            ));
        };
        let v = &h.elements[vertex];
        let scalar = |name: &[u8]| -> Result<Option<usize>, MeshFileError> {
            match v.property(name) {
                Some(k) => match v.properties[k].kind {
                    Kind::Scalar(_) => Ok(Some(k)),
                    Kind::List { .. } => Err(MeshFileError::at_line(
                        v.properties[k].line,
                        1,
                        format!(
                            "vertex property \"{}\" is a list: it must be a number",
                            shown(name)
                        ),
                    )),
                },
                None => Ok(None),
            }
        };
        let mut position = [0; 3];
        for (k, name) in [b"x", b"y", b"z"].into_iter().enumerate() {
            position[k] = scalar(name)?.ok_or_else(|| {
                at_element(
                    v,
                    format!("the vertex element has no \"{}\" property", shown(name)),
                )
            })?;
        }
        let all = |names: &[&[u8]]| -> Result<Option<Vec<usize>>, MeshFileError> {
            let found = names
                .iter()
                .map(|n| scalar(n))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(found.into_iter().collect())
        };
        let normal = all(&[b"nx", b"ny", b"nz"])?.map(|n| [n[0], n[1], n[2]]);
        let mut uv = None;
        for pair in [
            [&b"s"[..], b"t"],
            [b"u", b"v"],
            [b"texture_u", b"texture_v"],
            [b"texture_s", b"texture_t"],
        ] {
            if let Some(found) = all(&pair)? {
                uv = Some([found[0], found[1]]);
                break;
            }
        }
        let colour = all(&[b"red", b"green", b"blue"])?.map(|c| {
            [0, 1, 2].map(|k| {
                let divisor = match v.properties[c[k]].kind {
                    Kind::Scalar(ty) if ty.is_integer() => Some(ty.range().1 as f64),
                    _ => None,
                };
                (c[k], divisor)
            })
        });
        let face = match element(b"face") {
            None => {
                if let Some(e) = element(b"tristrips") {
                    return Err(at_element(
                        &h.elements[e],
                        "triangle strips (element \"tristrips\") are not supported: write faces"
                            .into(),
                    ));
                }
                None
            }
            Some(f) => {
                let e = &h.elements[f];
                let list = e
                    .property(b"vertex_indices")
                    .or_else(|| e.property(b"vertex_index"))
                    .ok_or_else(|| {
                        at_element(e, "the face element has no \"vertex_indices\" list".into())
                    })?;
                let p = &e.properties[list];
                match p.kind {
                    Kind::List { item, .. } if item.is_integer() => {}
                    Kind::List { item, .. } => {
                        return Err(MeshFileError::at_line(
                            p.line,
                            1,
                            format!(
                                "face property \"{}\" must hold integers, not {}",
                                shown(&p.name),
                                item.name()
                            ),
                        ))
                    }
                    Kind::Scalar(_) => {
                        return Err(MeshFileError::at_line(
                            p.line,
                            1,
                            format!("face property \"{}\" must be a list", shown(&p.name)),
                        ))
                    }
                }
                Some((f, list))
            }
        };
        Ok(Layout {
            vertex,
            position,
            normal,
            uv,
            colour,
            face,
        })
    }
}

/// Checks that the data can hold the elements the header declares, before any is read.
fn check_sizes(h: &Header, available: usize) -> Result<(), MeshFileError> {
    let ascii = h.encoding == Encoding::Ascii;
    // ASCII data may end without a final newline.
    let room = available + usize::from(ascii);
    let mut needed: usize = 0;
    for e in &h.elements {
        needed = e
            .count
            .checked_mul(e.min_size(ascii))
            .and_then(|n| n.checked_add(needed))
            .filter(|&n| n <= room)
            .ok_or_else(|| {
                MeshFileError::at_line(
                    e.line,
                    e.count_column,
                    format!(
                        "the header declares {}, more than the {available} bytes of data can hold",
                        e.counted(e.count)
                    ),
                )
            })?;
    }
    Ok(())
}

/// Values of the data, in order.
trait Values {
    /// Starts element `i` of `e`.
    fn begin(&mut self, e: &Element, i: usize) -> Result<(), MeshFileError>;
    /// The next value, of type `ty`, for property `p` of element `i` of `e`.
    fn value(
        &mut self,
        ty: Scalar,
        e: &Element,
        i: usize,
        p: &Property,
    ) -> Result<Num, MeshFileError>;
    /// Ends element `i` of `e`.
    fn end(&mut self, e: &Element, i: usize) -> Result<(), MeshFileError>;
    /// Checks that nothing follows the last element.
    fn finish(&mut self) -> Result<(), MeshFileError>;
    /// Where the last value read starts.
    fn last(&self) -> Location;
}

fn read(h: &Header, layout: &Layout, mut values: impl Values) -> Result<MeshData, MeshFileError> {
    let nv = h.elements[layout.vertex].count;
    let mut positions = Vec::with_capacity(nv);
    let mut normals = layout.normal.map(|_| Vec::with_capacity(nv));
    let mut uvs = layout.uv.map(|_| Vec::with_capacity(nv));
    let mut colours = layout.colour.map(|_| Vec::with_capacity(nv));
    let mut triangles = Vec::new();
    let mut row = Vec::new();
    // Where each value of `row` starts, for located position errors.
    let mut row_at = Vec::new();
    let mut corners = Vec::new();
    for (index, e) in h.elements.iter().enumerate() {
        if e.properties.is_empty() {
            continue;
        }
        for i in 0..e.count {
            values.begin(e, i)?;
            row.clear();
            row_at.clear();
            for (k, p) in e.properties.iter().enumerate() {
                match p.kind {
                    Kind::Scalar(ty) => {
                        row.push(values.value(ty, e, i, p)?);
                        row_at.push(values.last());
                    }
                    Kind::List { count, item } => {
                        let length = values.value(count, e, i, p)?;
                        let length_at = values.last();
                        let n = match length {
                            Num::Int(n) if n >= 0 => n as usize,
                            n => {
                                return Err(error_at(
                                    length_at,
                                    format!(
                                        "{} has a list \"{}\" of length {}",
                                        e.one(i),
                                        shown(&p.name),
                                        n.as_f64()
                                    ),
                                ))
                            }
                        };
                        let is_face_list = layout.face == Some((index, k));
                        if is_face_list {
                            corners.clear();
                        }
                        for _ in 0..n {
                            let x = values.value(item, e, i, p)?;
                            if is_face_list {
                                let Num::Int(v) = x else {
                                    unreachable!("checked integer type")
                                };
                                if v < 0 || v as u64 >= nv as u64 {
                                    return Err(error_at(
                                        values.last(),
                                        format!(
                                            "{} refers to vertex {v}, but the file has {}",
                                            e.one(i),
                                            h.elements[layout.vertex].counted(nv)
                                        ),
                                    ));
                                }
                                corners.push(v as u32);
                            }
                        }
                        if is_face_list {
                            if n < 3 {
                                return Err(error_at(
                                    length_at,
                                    format!(
                                        "{} has {n} vertices: a face needs at least 3",
                                        e.one(i)
                                    ),
                                ));
                            }
                            for c in 1..n - 1 {
                                triangles.push([corners[0], corners[c], corners[c + 1]]);
                            }
                        }
                        row.push(Num::Int(0));
                        row_at.push(length_at);
                    }
                }
            }
            values.end(e, i)?;
            if index == layout.vertex {
                let p = layout.position.map(|k| row[k].as_f64());
                for (axis, &k) in layout.position.iter().enumerate() {
                    check_position(p[axis], i, &e.properties[k].name, row_at[k])?;
                }
                positions.push(DVec3::from_array(p));
                if let (Some(n), Some(out)) = (layout.normal, &mut normals) {
                    let n = n.map(|k| row[k].as_f64() as f32);
                    out.push(Vec3::from_array(n));
                }
                if let (Some(t), Some(out)) = (layout.uv, &mut uvs) {
                    out.push(Vec2::new(
                        row[t[0]].as_f64() as f32,
                        row[t[1]].as_f64() as f32,
                    ));
                }
                if let (Some(c), Some(out)) = (layout.colour, &mut colours) {
                    out.push(Vec3::from_array(c.map(|(k, divisor)| {
                        let x = row[k].as_f64();
                        match divisor {
                            Some(d) => srgb_to_linear((x / d).clamp(0.0, 1.0)) as f32,
                            None => x as f32,
                        }
                    })));
                }
            }
        }
    }
    values.finish()?;
    if positions.is_empty() {
        normals = None;
        uvs = None;
        colours = None;
    }
    Ok(MeshData {
        positions,
        normals,
        uvs,
        uvs1: None,
        colours,
        tangents: None,
        triangles,
        materials: None,
        partial: Default::default(),
    })
}

/// Checks one coordinate `x` (property `name`) of vertex `i`, read at `at`: a position must
/// be a finite number within the f32 range (meshes are traced in f32).
fn check_position(x: f64, i: usize, name: &[u8], at: Location) -> Result<(), MeshFileError> {
    let expected = if !x.is_finite() {
        "a vertex position must be a finite number"
    } else if x.abs() > f64::from(f32::MAX) {
        "a vertex position must lie within the f32 range (±3.4e38)"
    } else {
        return Ok(());
    };
    Err(error_at(
        at,
        format!("vertex {i} has {} = {x:e}: {expected}", shown(name)),
    ))
}

/// The IEC 61966-2-1 sRGB decoding of `x` in [0, 1].
fn srgb_to_linear(x: f64) -> f64 {
    if x <= 0.04045 {
        x / 12.92
    } else {
        ((x + 0.055) / 1.055).powf(2.4)
    }
}

fn error_at(at: Location, message: String) -> MeshFileError {
    MeshFileError::Parse { at, message }
}

/// The lines of ASCII data (split at `\n`).
type Lines<'a> = std::slice::Split<'a, u8, fn(&u8) -> bool>;

/// ASCII data: one element per line, values separated by white space; blank lines between
/// elements are skipped.
struct Ascii<'a> {
    lines: std::iter::Peekable<Lines<'a>>,
    /// The current line, its number and the words left on it.
    line: &'a [u8],
    number: usize,
    words: std::vec::IntoIter<(usize, &'a [u8])>,
    last: Location,
}

impl<'a> Ascii<'a> {
    fn new(data: &'a [u8], first_line: usize) -> Self {
        let newline: fn(&u8) -> bool = |&b| b == b'\n';
        Ascii {
            lines: data.split(newline).peekable(),
            line: &[],
            number: first_line - 1,
            words: Vec::new().into_iter(),
            last: Location::Text {
                line: first_line,
                column: 1,
            },
        }
    }

    fn here(&self, offset: usize) -> Location {
        Location::Text {
            line: self.number,
            column: column(self.line, offset),
        }
    }
}

impl Values for Ascii<'_> {
    fn begin(&mut self, e: &Element, i: usize) -> Result<(), MeshFileError> {
        while let Some(line) = self.lines.next() {
            // The piece after a final newline is not a line.
            if line.is_empty() && self.lines.peek().is_none() {
                break;
            }
            self.number += 1;
            // Blank lines (empty or white space only) between elements are skipped.
            if line.iter().all(|b| b.is_ascii_whitespace()) {
                continue;
            }
            self.line = line.strip_suffix(b"\r").unwrap_or(line);
            self.words = words(self.line).into_iter();
            self.last = self.here(0);
            return Ok(());
        }
        Err(error_at(
            Location::Text {
                line: self.number + 1,
                column: 1,
            },
            format!(
                "the file ends after {} of the {} the header declares",
                e.counted(i),
                e.counted(e.count)
            ),
        ))
    }

    fn value(
        &mut self,
        ty: Scalar,
        e: &Element,
        i: usize,
        p: &Property,
    ) -> Result<Num, MeshFileError> {
        let Some((at, word)) = self.words.next() else {
            return Err(error_at(
                self.here(self.line.len()),
                format!(
                    "{} ends before its \"{}\" value ({})",
                    e.one(i),
                    shown(&p.name),
                    ty.name()
                ),
            ));
        };
        self.last = self.here(at);
        let text = std::str::from_utf8(word).ok();
        let value = if ty.is_integer() {
            let (lo, hi) = ty.range();
            text.and_then(|s| s.parse::<i64>().ok())
                .filter(|n| (lo..=hi).contains(n))
                .map(Num::Int)
        } else {
            text.and_then(|s| s.parse::<f64>().ok()).map(Num::Float)
        };
        value.ok_or_else(|| {
            error_at(
                self.last,
                format!(
                    "\"{}\" is not a {} (the \"{}\" value of {})",
                    shown(word),
                    ty.name(),
                    shown(&p.name),
                    e.one(i)
                ),
            )
        })
    }

    fn end(&mut self, e: &Element, i: usize) -> Result<(), MeshFileError> {
        match self.words.next() {
            Some((at, _)) => Err(error_at(
                self.here(at),
                format!("{} has more values than the header declares", e.one(i)),
            )),
            None => Ok(()),
        }
    }

    fn finish(&mut self) -> Result<(), MeshFileError> {
        while let Some(line) = self.lines.next() {
            self.number += 1;
            if let Some(at) = line.iter().position(|b| !b.is_ascii_whitespace()) {
                self.line = line;
                return Err(error_at(
                    self.here(at),
                    "the data goes on after the last element the header declares".into(),
                ));
            }
        }
        Ok(())
    }

    fn last(&self) -> Location {
        self.last
    }
}

/// Binary data.
struct Binary<'a> {
    data: &'a [u8],
    /// Offset of the data in the file.
    start: usize,
    pos: usize,
    last: usize,
    big_endian: bool,
}

impl Values for Binary<'_> {
    fn begin(&mut self, _: &Element, _: usize) -> Result<(), MeshFileError> {
        Ok(())
    }

    fn value(
        &mut self,
        ty: Scalar,
        e: &Element,
        i: usize,
        p: &Property,
    ) -> Result<Num, MeshFileError> {
        let size = ty.size();
        let Some(bytes) = self.data.get(self.pos..self.pos + size) else {
            return Err(error_at(
                Location::Byte((self.start + self.data.len()) as u64),
                format!(
                    "the file ends inside {} of the {} the header declares (its \"{}\" value)",
                    e.one(i),
                    e.counted(e.count),
                    shown(&p.name)
                ),
            ));
        };
        self.last = self.pos;
        self.pos += size;
        let mut b = [0u8; 8];
        b[..size].copy_from_slice(bytes);
        if self.big_endian {
            b[..size].reverse();
        }
        // `b` now holds the value little-endian in its first `size` bytes.
        Ok(match ty {
            Scalar::I8 => Num::Int((b[0] as i8).into()),
            Scalar::U8 => Num::Int(b[0].into()),
            Scalar::I16 => Num::Int(i16::from_le_bytes([b[0], b[1]]).into()),
            Scalar::U16 => Num::Int(u16::from_le_bytes([b[0], b[1]]).into()),
            Scalar::I32 => Num::Int(i32::from_le_bytes([b[0], b[1], b[2], b[3]]).into()),
            Scalar::U32 => Num::Int(u32::from_le_bytes([b[0], b[1], b[2], b[3]]).into()),
            Scalar::F32 => Num::Float(f32::from_le_bytes([b[0], b[1], b[2], b[3]]).into()),
            Scalar::F64 => Num::Float(f64::from_le_bytes(b)),
        })
    }

    fn end(&mut self, _: &Element, _: usize) -> Result<(), MeshFileError> {
        Ok(())
    }

    fn finish(&mut self) -> Result<(), MeshFileError> {
        let left = self.data.len() - self.pos;
        if left == 0 {
            return Ok(());
        }
        Err(error_at(
            Location::Byte((self.start + self.pos) as u64),
            format!(
                "{left} byte{} of data after the last element the header declares",
                if left == 1 { "" } else { "s" }
            ),
        ))
    }

    fn last(&self) -> Location {
        Location::Byte((self.start + self.last) as u64)
    }
}

#[cfg(test)]
mod tests;

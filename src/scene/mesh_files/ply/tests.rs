//! Tests of the PLY reader: exact located messages for bad headers and data, both
//! encodings reading the same mesh, and mutated files that never panic.
use super::*;

fn error(bytes: &[u8]) -> (Location, String) {
    match parse(bytes) {
        Err(MeshFileError::Parse { at, message }) => (at, message),
        other => panic!("expected a parse error, got {other:?}"),
    }
}

fn text(line: usize, column: usize) -> Location {
    Location::Text { line, column }
}

const HEAD: &str = "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\n\
                    property float y\nproperty float z\nelement face 1\n\
                    property list uchar int vertex_indices\nend_header\n";
const QUAD: &str = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n";

/// A binary file with the quad's header and data (`le`: little-endian).
fn binary(le: bool, x: Scalar) -> Vec<u8> {
    let (format, ty) = (
        if le {
            "binary_little_endian"
        } else {
            "binary_big_endian"
        },
        x.name(),
    );
    let mut out = format!(
        "ply\nformat {format} 1.0\ncomment made by a test\nelement vertex 4\n\
         property {ty} x\nproperty {ty} y\nproperty {ty} z\nproperty uchar red\n\
         element face 1\nproperty list uchar uint vertex_indices\nend_header\n"
    )
    .into_bytes();
    for p in [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0f64],
    ] {
        for c in p {
            match (x, le) {
                (Scalar::F32, true) => out.extend((c as f32).to_le_bytes()),
                (Scalar::F32, false) => out.extend((c as f32).to_be_bytes()),
                (_, true) => out.extend(c.to_le_bytes()),
                (_, false) => out.extend(c.to_be_bytes()),
            }
        }
        out.push(200);
    }
    out.push(4);
    for i in 0..4u32 {
        out.extend(if le { i.to_le_bytes() } else { i.to_be_bytes() });
    }
    out
}

#[test]
fn ascii_and_binary_read_the_same_quad() {
    let ascii = parse(format!("{HEAD}{QUAD}").as_bytes()).unwrap();
    assert_eq!(ascii.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert_eq!(ascii.positions[2], DVec3::new(1.0, 1.0, 0.0));
    assert_eq!((ascii.normals.as_ref(), ascii.uvs.as_ref()), (None, None));
    for le in [true, false] {
        for ty in [Scalar::F32, Scalar::F64] {
            assert_eq!(parse(&binary(le, ty)).unwrap(), ascii, "le {le} {ty:?}");
        }
    }
}

#[test]
fn normals_and_each_uv_spelling_are_read() {
    for (u, v) in [
        ("s", "t"),
        ("u", "v"),
        ("texture_u", "texture_v"),
        ("texture_s", "texture_t"),
    ] {
        let file = format!(
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\n\
             property double z\nproperty float nx\nproperty float ny\nproperty float nz\n\
             property float {u}\nproperty float {v}\nproperty uchar red\nproperty uchar green\n\
             property uchar blue\nelement face 1\nproperty list uchar int vertex_index\n\
             end_header\n0.1 0 0 0 0 1 0.25 0.5 255 0 0\n1 0 0 0 0 1 1 0 0 255 0\n\
             0 1 0 0 0 1 0 1 0 0 255\n3 0 1 2\n"
        );
        let m = parse(file.as_bytes()).unwrap();
        assert_eq!(m.positions[0], DVec3::new(0.1, 0.0, 0.0), "{u}");
        assert_eq!(m.normals.unwrap()[1], Vec3::Z);
        assert_eq!(m.uvs.unwrap()[0], Vec2::new(0.25, 0.5));
    }
}

#[test]
fn other_elements_are_read_past() {
    let file = "ply\nformat ascii 1.0\nelement material 1\nproperty list uchar float k\n\
                element vertex 3\nproperty int x\nproperty int y\nproperty int z\n\
                element face 1\nproperty uchar flags\nproperty list uchar int vertex_indices\n\
                property list uchar float texcoord\nelement edge 1\nproperty int vertex1\n\
                property int vertex2\nend_header\n2 0.5 0.5\n0 0 0\n1 0 0\n0 1 0\n\
                7 3 0 1 2 6 0 0 1 0 0 1\n0 1\n\n";
    let m = parse(file.as_bytes()).unwrap();
    assert_eq!(m.triangles, vec![[0, 1, 2]]);
    assert_eq!(m.positions[1], DVec3::X);
}

#[test]
fn a_point_cloud_has_no_triangles() {
    let file = "ply\r\nformat ascii 1.0\r\nelement vertex 1\r\nproperty float x\r\n\
                property float y\r\nproperty float z\r\nend_header\r\n1 2 3\r\n";
    let m = parse(file.as_bytes()).unwrap();
    assert_eq!(
        (m.positions, m.triangles),
        (vec![DVec3::new(1.0, 2.0, 3.0)], vec![])
    );
}

#[test]
fn bad_headers_are_located() {
    let cases: [(&str, Location, &str); 12] = [
        ("", text(1, 1), "a PLY file starts with the line \"ply\""),
        ("v 0 0 0\n", text(1, 1), "a PLY file starts with the line \"ply\""),
        ("ply\nelement vertex 3\n", text(2, 1), "the second line of a PLY header is \"format ENCODING 1.0\""),
        ("ply\nformat binary 1.0\n", text(2, 8), "the format is ascii, binary_little_endian or binary_big_endian"),
        ("ply\nformat ascii 2.0\n", text(2, 14), "PLY version 2.0 is not supported (only 1.0)"),
        ("ply\nformat ascii 1.0\nelement vertex -3\n", text(3, 16), "\"-3\" is not an element count (a whole number)"),
        ("ply\nformat ascii 1.0\nproperty float x\n", text(3, 1), "a property line must follow an element line"),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty real x\n",
            text(4, 10),
            "\"real\" is not a PLY type: use char, uchar, short, ushort, int, uint, float or double (or int8 … float64)",
        ),
        (
            "ply\nformat ascii 1.0\nelement face 1\nproperty list float int vertex_indices\n",
            text(4, 15),
            "a list's length has an integer type, not float",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n",
            text(5, 16),
            "element \"vertex\" has a second \"x\" property",
        ),
        ("ply\nformat ascii 1.0\nelement vertex 0\n", text(3, 17), "the header ends without an \"end_header\" line"),
        ("ply\nformat ascii 1.0\nvertex 3\n", text(3, 1), "\"vertex\" is not a PLY header line: expected element, property, comment, obj_info or end_header"),
    ];
    for (file, at, message) in cases {
        assert_eq!(
            error(file.as_bytes()),
            (at, message.to_string()),
            "{file:?}"
        );
    }
}

#[test]
fn headers_without_a_usable_mesh_are_located() {
    let base = "ply\nformat ascii 1.0\n";
    let cases: [(&str, Location, &str); 5] = [
        ("element face 0\nproperty list uchar int vertex_indices\nend_header\n", text(5, 1), "the header declares no \"vertex\" element"),
        ("element vertex 0\nproperty float x\nproperty float y\nend_header\n", text(3, 1), "the vertex element has no \"z\" property"),
        ("element vertex 0\nproperty list uchar float x\nend_header\n", text(4, 1), "vertex property \"x\" is a list: it must be a number"),
        (
            "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n",
            text(8, 1),
            "face property \"vertex_indices\" must hold integers, not float",
        ),
        (
            "element vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty int vertex_index\nend_header\n",
            text(8, 1),
            "face property \"vertex_index\" must be a list",
        ),
    ];
    for (file, at, message) in cases {
        let file = format!("{base}{file}");
        assert_eq!(
            error(file.as_bytes()),
            (at, message.to_string()),
            "{file:?}"
        );
    }
}

#[test]
fn counts_the_data_cannot_hold_are_rejected_before_reading() {
    let file = HEAD.replace("element vertex 4", "element vertex 4000000000000") + QUAD;
    assert_eq!(
        error(file.as_bytes()),
        (
            text(3, 16),
            "the header declares 4000000000000 vertices, more than the 34 bytes of data can hold"
                .into()
        )
    );
    let good = binary(true, Scalar::F32);
    let at = good
        .windows(14)
        .position(|w| w == b"element face 1")
        .unwrap();
    let b = [&good[..at], b"element face 99", &good[at + 14..]].concat();
    assert_eq!(
        error(&b),
        (
            text(9, 14),
            "the header declares 99 faces, more than the 69 bytes of data can hold".into()
        )
    );
}

#[test]
fn bad_ascii_data_is_located() {
    let with = |data: &str| format!("{HEAD}{data}");
    let cases: [(String, Location, &str); 7] = [
        (
            with("0 0 0\n1 0 0\n1 1\n0 1 0\n4 0 1 2 3\n"),
            text(12, 4),
            "vertex 2 ends before its \"z\" value (float)",
        ),
        (
            with("0 0 0\n1 0 0\n1 1 0 7\n0 1 0\n4 0 1 2 3\n"),
            text(12, 7),
            "vertex 2 has more values than the header declares",
        ),
        (
            with("0 0 0\n1 0 0\n1 x 0\n0 1 0\n4 0 1 2 3\n"),
            text(12, 3),
            "\"x\" is not a float (the \"y\" value of vertex 2)",
        ),
        (
            with("0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 4\n"),
            text(14, 9),
            "face 0 refers to vertex 4, but the file has 4 vertices",
        ),
        (
            with("0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 1\n"),
            text(14, 1),
            "face 0 has 2 vertices: a face needs at least 3",
        ),
        (
            with("0 0 0\n1 0 0                            \n"),
            text(12, 1),
            "the file ends after 2 vertices of the 4 vertices the header declares",
        ),
        (
            with(&format!("{QUAD}\n3 0 1 2\n")),
            text(16, 1),
            "the data goes on after the last element the header declares",
        ),
    ];
    for (file, at, message) in cases {
        assert_eq!(
            error(file.as_bytes()),
            (at, message.to_string()),
            "{file:?}"
        );
    }
    let big = with("0 0 0\n1 0 0\n1 1 0\n0 1 0\n256 0 1 2 3\n");
    assert_eq!(
        error(big.as_bytes()),
        (
            text(14, 1),
            "\"256\" is not a uchar (the \"vertex_indices\" value of face 0)".into()
        )
    );
}

#[test]
fn bad_binary_data_is_located_by_byte() {
    let good = binary(true, Scalar::F32);
    let cut = &good[..good.len() - 3];
    assert_eq!(
        error(cut),
        (
            Location::Byte(cut.len() as u64),
            "the file ends inside face 0 of the 1 face the header declares (its \"vertex_indices\" value)"
                .into()
        )
    );
    let mut bad = good.clone();
    let last = bad.len() - 4;
    bad[last..].copy_from_slice(&7u32.to_le_bytes());
    assert_eq!(
        error(&bad),
        (
            Location::Byte(last as u64),
            "face 0 refers to vertex 7, but the file has 4 vertices".into()
        )
    );
    let mut long = good.clone();
    long.extend([0, 0]);
    assert_eq!(
        error(&long),
        (
            Location::Byte(good.len() as u64),
            "2 bytes of data after the last element the header declares".into()
        )
    );
}

/// Bit flips, cuts and insertions in valid files never panic and never produce an index
/// out of range.
#[test]
fn mutated_files_are_read_or_rejected() {
    let seeds = [
        format!("{HEAD}{QUAD}").into_bytes(),
        binary(true, Scalar::F32),
        binary(false, Scalar::F64),
    ];
    let mut s: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        s
    };
    for k in 0..6000 {
        let mut f = seeds[k % seeds.len()].clone();
        for _ in 0..1 + next() % 4 {
            let at = (next() as usize) % f.len().max(1);
            match next() % 4 {
                0 if !f.is_empty() => f[at] ^= 1 << (next() % 8),
                1 => f.truncate(at),
                2 => f.insert(at.min(f.len()), next() as u8),
                _ if !f.is_empty() => f[at] = b"0123456789 \n-."[(next() % 14) as usize],
                _ => {}
            }
        }
        if let Ok(m) = parse(&f) {
            let n = m.positions.len() as u32;
            assert!(m.triangles.iter().flatten().all(|&i| i < n));
            assert!(m.normals.is_none_or(|v| v.len() == n as usize));
            assert!(m.uvs.is_none_or(|v| v.len() == n as usize));
        }
    }
}

/// A vertex position that is NaN, infinite or beyond the f32 range is an error at its
/// value (line and column in ASCII, byte offset in binary files).
#[test]
fn non_finite_positions_are_located() {
    let with = |data: &str| format!("{HEAD}{data}");
    let cases = [
        (
            "0 0 0\n1 0 0\nnan 1 0\n0 1 0\n4 0 1 2 3\n",
            text(12, 1),
            "x = NaN",
        ),
        (
            "0 0 0\n1 0 0\n1  -inf 0\n0 1 0\n4 0 1 2 3\n",
            text(12, 4),
            "y = -inf",
        ),
        (
            "0 0 0\n1 0 0\n1 1 0\n0 1 inf\n4 0 1 2 3\n",
            text(13, 5),
            "z = inf",
        ),
    ];
    for (data, at, value) in cases {
        let vertex = if at == text(13, 5) { 3 } else { 2 };
        assert_eq!(
            error(with(data).as_bytes()),
            (
                at,
                format!("vertex {vertex} has {value}: a vertex position must be a finite number")
            ),
            "{data:?}"
        );
    }
    assert_eq!(
        error(with("0 0 0\n1 0 0\n1 1 0\n0 1e39 0\n4 0 1 2 3\n").as_bytes()),
        (
            text(13, 3),
            "vertex 3 has y = 1e39: a vertex position must lie within the f32 range (±3.4e38)"
                .into()
        )
    );
    // Binary: vertex 2's x (each vertex is 3 floats and a uchar, 13 bytes).
    let mut bad = binary(true, Scalar::F32);
    let data = bad.len() - (4 * 13 + 1 + 16);
    let at = data + 2 * 13;
    bad[at..at + 4].copy_from_slice(&f32::NAN.to_le_bytes());
    assert_eq!(
        error(&bad),
        (
            Location::Byte(at as u64),
            "vertex 2 has x = NaN: a vertex position must be a finite number".into()
        )
    );
}

/// ASCII data holds one element per line; blank lines between elements (empty, white space,
/// `\r`) are skipped, wherever they are.
#[test]
fn blank_lines_between_elements_are_skipped() {
    for data in [
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n\n4 0 1 2 3\n",
        "\n0 0 0\n  \t\n1 0 0\n1 1 0\r\n\r\n0 1 0\n4 0 1 2 3\n\n\n",
        "0 0 0\n1 0 0\n1 1 0\n0 1 0\n \n4 0 1 2 3",
    ] {
        let m =
            parse(format!("{HEAD}{data}").as_bytes()).unwrap_or_else(|e| panic!("{data:?}: {e}"));
        assert_eq!(m.positions.len(), 4, "{data:?}");
        assert_eq!(m.triangles, [[0, 1, 2], [0, 2, 3]], "{data:?}");
    }
    // The end of the data is still found after blank lines, and counted lines include them.
    assert_eq!(
        error(format!("{HEAD}0 0 0\n\n1 0 0          \n          \n").as_bytes()),
        (
            text(14, 1),
            "the file ends after 2 vertices of the 4 vertices the header declares".into()
        )
    );
    // An element is one line: values split over two lines are still an error.
    assert_eq!(
        error(format!("{HEAD}0 0 0\n1 0\n0\n1 1 0\n0 1 0\n4 0 1 2 3\n").as_bytes()).1,
        "vertex 1 ends before its \"z\" value (float)"
    );
}

/// Trailing blanks after the first line's `ply` are allowed, as after every other header
/// line (a file whose first line was `ply ` was refused).
#[test]
fn the_magic_line_may_end_in_blanks() {
    for magic in ["ply ", "ply\t", "ply \r"] {
        let file = format!("{magic}\n{}{QUAD}", &HEAD[4..]);
        let m = parse(file.as_bytes()).unwrap_or_else(|e| panic!("{magic:?}: {e:?}"));
        assert_eq!(m.positions.len(), 4, "{magic:?}");
    }
}

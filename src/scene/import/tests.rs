//! The seam with a second format: a tiny test-only reader (`.pts`, one element per line,
//! `<kind> <RON of the element>`) that records positions in a [`PathTable`] as it parses.
//! Its elements go through the shared validation and print exactly like RON ones, at the
//! positions it recorded.

use std::path::Path;

use serde::de::DeserializeOwned;

use super::{parent, Format, PathTable, ReadScene, SourcePos, FORMATS};
use crate::scene::desc::SceneDesc;
use crate::scene::load;
use crate::scene::message::Diagnostic;

/// RON's table plus the fake format.
const WITH_FAKE: &[Format] = &[
    FORMATS[0],
    Format {
        name: "fake",
        extensions: &["pts"],
        read: read_fake,
        syntax: crate::scene::syntax::Syntax::Ron,
    },
];

fn element<T: DeserializeOwned>(text: &str) -> Result<T, String> {
    ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .from_str(text)
        .map_err(|e| e.code.to_string())
}

/// `(field: value, …)`: each top-level field and the 0-based char offset of its value.
fn fields(text: &str) -> Vec<(String, usize)> {
    let chars: Vec<char> = text.chars().collect();
    let (mut depth, mut out, mut i) = (0usize, Vec::new(), 0);
    while i < chars.len() {
        match chars[i] {
            '(' | '[' => depth += 1,
            ')' | ']' => depth = depth.saturating_sub(1),
            c if depth == 1 && (c.is_alphabetic() || c == '_') => {
                let start = i;
                while i < chars.len() && (chars[i].is_alphanumeric() || chars[i] == '_') {
                    i += 1;
                }
                if chars.get(i) == Some(&':') {
                    let name: String = chars[start..i].iter().collect();
                    i += 1;
                    while chars.get(i) == Some(&' ') {
                        i += 1;
                    }
                    out.push((name, i));
                }
                continue;
            }
            _ => {}
        }
        i += 1;
    }
    out
}

/// The fake format's reader: every unparsable line is an error (all collected), an unknown
/// kind is a located warning.
fn read_fake(path: &Path, bytes: &[u8]) -> Result<ReadScene, super::ReadFailure> {
    let text = std::str::from_utf8(bytes).map_err(|_| super::ReadFailure::default())?;
    let mut desc = SceneDesc::default();
    let mut table = PathTable::default();
    let (mut errors, mut warnings) = (Vec::new(), Vec::new());
    let at = |line: usize, column: usize| SourcePos {
        file: path.to_path_buf(),
        line,
        column,
    };
    for (l, line) in text.lines().enumerate() {
        let Some((kind, rest)) = line.split_once(' ') else {
            continue;
        };
        let body = kind.len() + 2;
        macro_rules! list {
            ($list:ident, $what:literal) => {{
                match element(rest) {
                    Ok(e) => {
                        let path = format!(concat!($what, "[{}]"), desc.$list.len());
                        desc.$list.push(e);
                        for (field, offset) in fields(rest) {
                            table.insert(format!("{path}.{field}"), at(l + 1, body + offset));
                        }
                        table.insert(path, at(l + 1, 1));
                    }
                    Err(m) => errors.push(Diagnostic::at(at(l + 1, body), m, None)),
                }
            }};
        }
        match kind {
            "camera" => list!(cameras, "cameras"),
            "light" => list!(lights, "lights"),
            "object" => list!(objects, "objects"),
            "instance" => list!(instances, "instances"),
            "group" => list!(groups, "groups"),
            "render" => match element(rest) {
                Ok(r) => {
                    desc.render = Some(r);
                    table.insert("render", at(l + 1, 1));
                }
                Err(m) => errors.push(Diagnostic::at(at(l + 1, body), m, None)),
            },
            other => warnings.push(Diagnostic::at(
                at(l + 1, 1),
                format!("ignored request \"{other}\""),
                None,
            )),
        }
    }
    if !errors.is_empty() {
        return Err(super::ReadFailure { errors, warnings });
    }
    Ok(ReadScene {
        desc,
        map: table.into_map(path),
        warnings,
        read_files: Vec::new(),
    })
}

const CAMERA: &str = "(name: \"cam\", fov_y: 40, resolution: (8, 8), placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)))";
const OBJECT: &str = "(name: \"tri\", mesh: Inline(vertices: [(0, 0, 0), (1, 0, 0), (0, 1, 0)], polygons: [[0, 1, 2]]))";

fn fake_scene(light: &str) -> String {
    format!(
        "camera {CAMERA}\nlight {light}\nhider (stochastic)\nobject {OBJECT}\n\
         instance (name: \"a\", of: \"tri\")\ngroup (name: \"world\", members: [\"a\"])\n\
         render (root: \"world\", camera: \"cam\")\n"
    )
}

fn ron_scene(light: &str) -> String {
    format!(
        "Scene(\ncameras: [{CAMERA}],\nlights: [{light}],\nobjects: [{OBJECT}],\n\
         instances: [(name: \"a\", of: \"tri\")],\ngroups: [(name: \"world\", members: [\"a\"])],\n\
         render: (root: \"world\", camera: \"cam\"),\n)"
    )
}

fn errors(text: &str, path: &str) -> Vec<String> {
    match load(Path::new(path), Some(text), WITH_FAKE, &Default::default()) {
        Ok(_) => panic!("{path} loaded"),
        Err(e) => e.0.iter().map(ToString::to_string).collect(),
    }
}

const BAD_LIGHT: &str =
    "(name: \"key\", kind: Point(position: (0, 5, 0)), color: (1, -1, 0.5), intensity: -2)";

#[test]
fn a_validation_error_in_another_format_prints_like_ron_at_its_recorded_position() {
    // The fake reader recorded `lights[0].color` and `lights[0].intensity` at their values;
    // validation asks for `lights[0].color[1]`, which falls back to `lights[0].color`.
    assert_eq!(
        errors(&fake_scene(BAD_LIGHT), "scene.pts"),
        [
            "scene.pts:2:62: error: color must not be negative, found -1\n  help: color takes 0 or more: write 1 if only the sign is wrong",
            "scene.pts:2:87: error: intensity must not be negative, found -2\n  help: intensity takes 0 or more: write 2 if only the sign is wrong",
        ]
    );
    // The same light in RON: the same messages, at RON's positions (RON's index knows the
    // tuple items, so `color[1]` is the `-1` itself).
    assert_eq!(
        errors(&ron_scene(BAD_LIGHT), "scene.ron"),
        [
            "scene.ron:3:69: error: color must not be negative, found -1\n  help: color takes 0 or more: write 1 if only the sign is wrong",
            "scene.ron:3:90: error: intensity must not be negative, found -2\n  help: intensity takes 0 or more: write 2 if only the sign is wrong",
        ]
    );
}

#[test]
fn other_format_elements_carry_their_positions_and_warnings_are_located() {
    let light = "(name: \"key\", kind: Point(position: (0, 5, 0)))";
    let scene = load(
        Path::new("scene.pts"),
        Some(&fake_scene(light)),
        WITH_FAKE,
        &Default::default(),
    )
    .unwrap();
    assert_eq!(
        scene.located_warnings,
        ["scene.pts:3:1: warning: ignored request \"hider\""]
    );
    let mut q = scene
        .world
        .query::<(&crate::components::Name, &crate::components::SourceLink)>();
    let mut links: Vec<String> = q
        .iter()
        .map(|(n, l)| format!("{} {}:{}", n.0, l.line, l.column))
        .collect();
    links.sort();
    // The built-in material has no element: the root file's start.
    assert_eq!(
        links,
        [
            "<default> 1:1",
            "cam 1:1",
            "key 2:1",
            "tri 4:1",
            "world/a 5:1"
        ]
    );
}

#[test]
fn unknown_extensions_are_located_errors_naming_the_known_formats() {
    assert_eq!(
        errors("", "scene.xyz"),
        ["scene.xyz:1:1: error: unknown scene format \".xyz\"\n  help: known scene formats: .ron, .pts"]
    );
    assert_eq!(
        errors("Scene(include: [\"lib/a.XYZ\"])", "dir/main.ron"),
        ["dir/main.ron:1:17: error: cannot read include file \"dir/lib/a.XYZ\": unknown scene format \".xyz\"\n  help: known scene formats: .ron, .pts"]
    );
    assert_eq!(
        errors("", "Makefile"),
        ["Makefile:1:1: error: no file extension to choose a scene format by\n  help: known scene formats: .ron, .pts"]
    );
}

#[test]
fn reader_errors_are_all_reported_and_unrecorded_paths_fall_back_to_the_file() {
    let text = "light (name: 1)\ncamera (fov_y: \"wide\")\n";
    let got = errors(text, "s.pts");
    assert_eq!(got.len(), 2, "{got:?}");
    assert!(got[0].starts_with("s.pts:1:7: error: "), "{got:?}");
    assert!(got[1].starts_with("s.pts:2:8: error: "), "{got:?}");
    // Nothing recorded: the file's start. No render entry is reported there.
    assert_eq!(
        errors("hider (x)\n", "s.pts"),
        ["s.pts:1:1: error: the scene has no render entry\n  help: add `render: (root: \"<group>\", camera: \"<camera>\")`"]
    );
}

#[test]
fn parent_paths_step_up_one_segment() {
    let mut p = Some("objects[3].mesh.Sphere.radius");
    let mut seen = Vec::new();
    while let Some(q) = p {
        seen.push(q);
        p = parent(q);
    }
    assert_eq!(
        seen,
        [
            "objects[3].mesh.Sphere.radius",
            "objects[3].mesh.Sphere",
            "objects[3].mesh",
            "objects[3]",
            "objects",
            ""
        ]
    );
}

//! RON written by hand, the way a tester wrote it: each mistake reported as what it is, at
//! the place to fix it — shader nodes called in the wrong style, a file ending inside an
//! unclosed bracket, a `(` left open before the next field or element, a list left open,
//! `Box()`, `Obj("x.obj")`, a missing comma, text after the scene, a `#` comment, a block
//! comment left open, a tuple with an extra value — and the loader's nits
//! (a missing image file, a non-finite node input, a directory given as a scene, a palette
//! PNG without its palette, an EXR displacement).

use std::path::Path;

use stagelight::scene::load_scene_str;

/// The first error of `text` read as `s.ron`.
fn first_error(text: &str) -> String {
    let errors = load_scene_str(text, Path::new("s.ron"))
        .err()
        .unwrap_or_else(|| panic!("loaded without errors:\n{text}"));
    errors.0[0].to_string()
}

/// A scene whose material binds `albedo` to `input`, on one line (line 3).
fn bound(input: &str) -> String {
    format!(
        "Scene(\n  cameras: [(name: \"c\", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)))],\n  materials: [(name: \"m\", shader: Lambert(albedo: (1, 1, 1)), bind: {{\"albedo\": {input}}})],\n  objects: [(name: \"q\", mesh: Sphere(radius: 1), material: \"m\")],\n  instances: [(name: \"i\", of: \"q\")],\n  groups: [(name: \"w\", members: [\"i\"])],\n  render: (root: \"w\", camera: \"c\"),\n)\n"
    )
}

/// Column of the bound input on line 3.
const INPUT: usize = 80;

#[test]
fn nodes_called_in_the_wrong_style_name_their_form() {
    let positional = "help: write the inputs without names, in that order";
    for (input, message) in [
        (
            "Channel(input: Uv, channel: 1)",
            "Channel takes its inputs in order: Channel(<colour>, <channel index>)",
        ),
        // `ron` said `unknown node "c"` here.
        (
            "Luminance(c: Uv)",
            "Luminance takes its inputs in order: Luminance(<colour>)",
        ),
        (
            "Add(a: Uv, b: 1)",
            "Add takes its inputs in order: Add(<a>, <b>)",
        ),
    ] {
        assert_eq!(
            first_error(&bound(input)),
            format!("s.ron:3:{INPUT}: error: {message}\n  {positional}"),
            "{input}"
        );
    }
    // Nested: the inner node is named.
    assert_eq!(
        first_error(&bound("Mix(a: Uv, b: 1, t: Channel(c: Uv, k: 0))")),
        format!(
            "s.ron:3:{}: error: Channel takes its inputs in order: Channel(<colour>, <channel index>)\n  {positional}",
            INPUT + 20
        )
    );
    for (input, message) in [
        (
            "Mix((1, 0, 0), 1)",
            "Mix takes named inputs: Mix(a: …, b: …, t: …)",
        ),
        (
            "Convert((1, 0, 0))",
            "Convert takes named inputs: Convert(input: …, from: Rgb, to: Rgb)",
        ),
        (
            "Image(\"ok.png\")",
            "Image takes named fields: Image(file: \"ok.png\")",
        ),
    ] {
        let name = input.split('(').next().unwrap();
        assert_eq!(
            first_error(&bound(input)),
            format!("s.ron:3:{INPUT}: error: {message}\n  help: write each field as `name: value`; docs/scene-format.md lists the fields of {name}"),
            "{input}"
        );
    }
    // The documented forms still load (positional `Mix` as before).
    for input in [
        "Channel(Uv, 1)",
        "Mix(a: Uv, b: 1, t: 0.5)",
        "Mix(Uv, 1, 0.5)",
    ] {
        assert!(
            load_scene_str(&bound(input), Path::new("s.ron")).is_ok(),
            "{input}"
        );
    }
}

#[test]
fn named_field_nodes_called_in_order_name_their_form_at_the_call() {
    // `ron` said `unknown field "Uv" in Mix` (at the `Uv`), `found invalid std identifier
    // "8", try the raw identifier `r#8` instead`, `expected comma` or `expected colon`.
    for (input, form) in [
        ("Mix(Uv, 1)", "Mix(a: …, b: …, t: …)"),
        ("Mix(1, Uv)", "Mix(a: …, b: …, t: …)"),
        ("Mix(a: Uv, Uv)", "Mix(a: …, b: …, t: …)"),
        ("Smoothstep(Uv, 1)", "Smoothstep(edge0: …, edge1: …, x: …)"),
        ("Convert(Uv)", "Convert(input: …, from: Rgb, to: Rgb)"),
        ("Checker(8)", "Checker(uv: Uv, scale: 2, a: 1, b: 0)"),
        (
            "Disk(Uv)",
            "Disk(uv: Uv, center: (0.5, 0.5), radius: 0.4, fuzz: 0, inside: (0, 0, 1), outside: (1, 0, 0))",
        ),
        ("Steps(2)", "Steps(uv: Uv, steps: 4, fuzz: 0.05)"),
        ("Repeat(Uv, scale: 3)", "Repeat(uv: Uv, scale: 10)"),
        ("Noise(2)", "Noise(p: Position, frequency: 1, seed: 0)"),
        (
            "Fbm(Position)",
            "Fbm(p: Position, frequency: 1, octaves: 4, lacunarity: 2, gain: 0.5, seed: 0)",
        ),
        (
            "Turbulence(Position)",
            "Turbulence(p: Position, frequency: 1, octaves: 4, lacunarity: 2, gain: 0.5, seed: 0)",
        ),
    ] {
        let name = input.split('(').next().unwrap();
        assert_eq!(
            first_error(&bound(input)),
            format!("s.ron:3:{INPUT}: error: {name} takes named inputs: {form}\n  help: write each field as `name: value`; docs/scene-format.md lists the fields of {name}"),
            "{input}"
        );
    }
    for (input, form) in [
        ("Image(Uv)", "Image(file: \"…\")"),
        ("Alpha(Uv)", "Alpha(file: \"…\")"),
    ] {
        let name = input.split('(').next().unwrap();
        assert_eq!(
            first_error(&bound(input)),
            format!("s.ron:3:{INPUT}: error: {name} takes named fields: {form}\n  help: write each field as `name: value`; docs/scene-format.md lists the fields of {name}"),
            "{input}"
        );
    }
    // Nested: the inner call is reported; a misspelt field keeps `ron`'s message.
    assert_eq!(
        first_error(&bound("Mix(a: Checker(8), b: 1, t: 0.5)")),
        format!("s.ron:3:{}: error: Checker takes named inputs: Checker(uv: Uv, scale: 2, a: 1, b: 0)\n  help: write each field as `name: value`; docs/scene-format.md lists the fields of Checker", INPUT + 7)
    );
    assert_eq!(
        first_error(&bound("Checker(sclae: 2)")),
        format!(
            "s.ron:3:{}: error: unknown field \"sclae\" in Checker\n  help: did you mean \"scale\"?",
            INPUT + 8
        )
    );
}

/// A minimal scene, its lines as written.
const SCENE: &[&str] = &[
    "Scene(",
    "  cameras: [(name: \"c\", fov_y: 40, resolution: (4, 4), placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)))],",
    "  objects: [(name: \"q\", mesh: Sphere(radius: 1))],",
    "  instances: [(name: \"i\", of: \"q\")],",
    "  groups: [(name: \"w\", members: [\"i\"])],",
    "  render: (root: \"w\", camera: \"c\"),",
    ")",
];

/// [`SCENE`] with line `line` (1-based) replaced.
fn with_line(line: usize, text: &str) -> String {
    let mut lines: Vec<&str> = SCENE.to_vec();
    lines[line - 1] = text;
    lines.join("\n") + "\n"
}

#[test]
fn syntax_errors_say_what_is_missing_where() {
    assert!(load_scene_str(&with_line(1, "Scene("), Path::new("s.ron")).is_ok());
    let cases = [
        // `render: (` never closed: `ron` said "expected comma" at 8:1 of a 7-line file.
        (
            with_line(6, "  render: (root: \"w\", camera: \"c\","),
            "s.ron:7:2: error: the file ends inside an unclosed `(`\n  help: the `(` opened at 6:11 is not closed: close it with `)`",
        ),
        // The scene's own `(` never closed.
        (
            SCENE[..6].join("\n") + "\n",
            "s.ron:6:36: error: the file ends inside an unclosed `(`\n  help: the `(` opened at 1:6 is not closed: close it with `)`",
        ),
        // `ron` said "expected Group(…) but found render(…)".
        (
            with_line(5, "  groups: [(name: \"w\", members: [\"i\"]),"),
            "s.ron:6:3: error: the list opened at 5:11 is not closed\n  help: add `]` before `render:`",
        ),
        (
            with_line(3, "  objects: [(name: \"q\", mesh: Obj(\"x.obj\"))],"),
            "s.ron:3:31: error: Obj takes named fields: Obj(file: \"x.obj\")\n  help: write each field as `name: value`; docs/scene-format.md lists the fields of Obj",
        ),
        // A missing comma at the end of a line (and a comment after it).
        (
            with_line(4, "  instances: [(name: \"i\", of: \"q\")] // the instance"),
            "s.ron:4:36: error: expected comma\n  help: add ',' here",
        ),
        (
            with_line(7, ");"),
            "s.ron:7:2: error: unexpected text after the scene\n  help: there is text after the scene's closing `)` at 7:1; a file holds exactly one `Scene(...)`: delete the text after it",
        ),
    ];
    for (text, expected) in cases {
        assert_eq!(first_error(&text), expected, "\n{text}");
    }
    let boxed = SCENE
        .join("\n")
        .replace("Scene(", "Scene(\n  options: (filter: Box()),");
    assert_eq!(
        first_error(&boxed),
        "s.ron:2:21: error: Box takes no value: write it bare as Box\n  help: delete the `(…)` after Box"
    );
}

#[test]
fn an_unclosed_parenthesis_before_the_next_field_or_element_is_named_where_it_opened() {
    let scene = SCENE.join("\n") + "\n";
    let first = |prefix: &str| first_error(&scene.replace("Scene(", &format!("Scene(\n{prefix}")));
    // A node call: `ron` said `unknown field "bind" in Lambert`.
    assert_eq!(
        first("  materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5), bind: {\"albedo\": Uv})],"),
        "s.ron:2:68: error: the `(` of Lambert opened at 2:42 is not closed\n  help: close it with `)` at 2:66, before `bind:`"
    );
    // A material tuple before the next element: `ron` said `expected identifier`.
    assert_eq!(
        first("  materials: [\n    (name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5)),\n    (name: \"n\", shader: Plastic()),\n  ],"),
        "s.ron:4:5: error: the `(` opened at 3:5 is not closed\n  help: close it with `)` at 3:57, before `(`"
    );
    // The options struct: `ron` said `unknown field "cameras" in Options`.
    assert_eq!(
        first("  options: (samples: 4, filter: Box,"),
        "s.ron:3:3: error: the `(` of `options:` opened at 2:12 is not closed\n  help: close it with `)` at 2:36, before `cameras:`"
    );
    // A closer of another kind: `ron` said `expected comma`.
    assert_eq!(
        first_error(&with_line(3, "  objects: [(name: \"q\", mesh: Sphere(radius: 1)],")),
        "s.ron:3:48: error: the `(` opened at 3:13 is not closed\n  help: close it with `)` at 3:48, before `]`"
    );
    // A list element and its list: `ron` said `unknown field "render" in Group`.
    assert_eq!(
        first_error(&with_line(5, "  groups: [(name: \"w\", members: [\"i\"],")),
        "s.ron:6:3: error: the `(` opened at 5:12 and the `[` opened at 5:11 are not closed\n  help: close them with `)]` at 5:38, before `render:`"
    );
    // A misspelt field is not an unclosed bracket: closing one does not get past it.
    assert_eq!(
        first("  materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5), bnd: 1)],"),
        "s.ron:2:68: error: unknown field \"bnd\" in Lambert\n  help: expected \"albedo\""
    );
}

#[test]
fn a_hash_comment_is_named_at_the_hash() {
    let scene = SCENE.join("\n") + "\n";
    let help = "help: RON comments are `// …` (to the end of the line) and `/* … */`: write `//` instead of `#`";
    // `ron` said `Scene takes named fields: Scene(<field>: <value>, …)` at 1:1 for the first,
    // `expected identifier` for the others.
    for (text, at) in [
        (scene.replace("Scene(", "Scene(\n    # main camera"), "2:5"),
        (
            scene.replace("  groups:", "  # a comment in the middle\n  groups:"),
            "5:3",
        ),
        (
            with_line(4, "  instances: [(name: \"i\", of: \"q\")], # the instance"),
            "4:38",
        ),
    ] {
        assert_eq!(
            first_error(&text),
            format!("s.ron:{at}: error: `#` does not start a comment in RON\n  {help}"),
            "\n{text}"
        );
    }
    // A `#` in a string or a comment is no comment.
    let fine = with_line(
        3,
        "  objects: [(name: \"q#1\", mesh: Sphere(radius: 1))], // # 1",
    )
    .replace("of: \"q\"", "of: \"q#1\"");
    assert!(load_scene_str(&fine, Path::new("s.ron")).is_ok());
}

#[test]
fn an_unclosed_block_comment_is_named_where_it_opens() {
    // `ron` said `the file ends inside an unclosed `(`` at the end of the file for both.
    let nested = SCENE
        .join("\n")
        .replace("Scene(", "Scene(\n    /* note: a /* nested */ comment");
    assert_eq!(
        first_error(&nested),
        "s.ron:2:5: error: unclosed block comment: the file ends inside it\n  help: RON block comments nest: the `/*` at 2:16 opens a comment inside this one, and a `*/` closes only the innermost open comment; remove that `/*` or give it its own `*/`"
    );
    let trailing =
        SCENE[..5].join("\n") + "\n  render: (root: \"w\", camera: \"c\"), /* trailing\n";
    assert_eq!(
        first_error(&trailing),
        "s.ron:6:37: error: unclosed block comment: the file ends inside it\n  help: close it with `*/` (RON block comments nest: each `/*` inside it needs its own `*/`)"
    );
    // Nested comments that close load.
    let closed = nested.replace("comment", "comment */");
    assert!(load_scene_str(&closed, Path::new("s.ron")).is_ok());
}

#[test]
fn a_tuple_with_an_extra_value_is_named_at_the_value() {
    let scene = SCENE.join("\n") + "\n";
    let first = |line: &str| first_error(&scene.replace("Scene(", &format!("Scene(\n{line}")));
    // `ron` said `expected closing `)`` / `close the `(` with `)``.
    assert_eq!(
        first("  materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5, 0.5, 1)))],"),
        "s.ron:2:67: error: expected a tuple of size 3 but found 4 elements\n  help: remove the extra value: colours are RGB, write exactly 3 values in `(…)` (no alpha)"
    );
    assert_eq!(
        first("  materials: [(name: \"m\", shader: Lambert(albedo: (1, 1, 1, 0, 0)))],"),
        "s.ron:2:61: error: expected a tuple of size 3 but found 5 elements\n  help: remove the 2 extra values: colours are RGB, write exactly 3 values in `(…)` (no alpha)"
    );
    assert_eq!(
        first("  lights: [(name: \"k\", kind: Point(position: (0, 4, 2, 1)))],"),
        "s.ron:2:56: error: expected a tuple of size 3 but found 4 elements\n  help: remove the extra value: write exactly 3 values in `(…)`"
    );
    assert_eq!(
        first_error(&with_line(2, "  cameras: [(name: \"c\", fov_y: 40, resolution: (4, 4, 3), placement: LookAt(eye: (0, 0, 5), target: (0, 0, 0), up: (0, 1, 0)))],")),
        "s.ron:2:55: error: expected a tuple of size 2 but found 3 elements\n  help: remove the extra value: write exactly 2 values in `(…)`"
    );
    // Too few, as `ron` says it.
    assert_eq!(
        first("  materials: [(name: \"m\", shader: Lambert(albedo: (0.5, 0.5)))],"),
        "s.ron:2:60: error: expected a tuple of size 3 but found 2 elements\n  help: write exactly 3 values in `(…)`"
    );
}

#[test]
fn a_missing_image_and_a_non_finite_input_are_named() {
    assert_eq!(
        first_error(&bound("Image(file: \"tests/fixtures/nowhere.png\")")),
        format!("s.ron:3:{}: error: cannot read image file \"tests/fixtures/nowhere.png\": file not found\n  help: image textures are PNG files, or EXR files with R, G and B, Y or a single channel, relative to the scene file", INPUT + 12)
    );
    // It said "a number must be a finite number".
    assert_eq!(
        first_error(&bound("Checker(scale: NaN)")),
        format!(
            "s.ron:3:{}: error: scale must be a finite number, found NaN",
            INPUT + 15
        )
    );
}

#[test]
fn a_displacement_image_that_is_not_an_image_says_what_displacement_reads() {
    let dir = crate::common::scratch_dir("ron-syntax-displacement");
    std::fs::write(dir.join("h.exr"), b"v/1\x01 not really").unwrap();
    let text = with_line(
        3,
        "  objects: [(name: \"q\", mesh: Sphere(radius: 1), displacement: (shader: Image(file: \"h.exr\")))],",
    );
    let path = dir.join("s.ron");
    std::fs::write(&path, text).unwrap();
    let err = stagelight::scene::load_scene(&path).err().expect("refused");
    assert_eq!(
        err.0[0].to_string(),
        format!(
            "{}:3:85: error: cannot read image file \"{}\": not a readable OpenEXR image (not supported: too new file feature flags)\n  help: displacement images are PNG files (read as grey 0…1) or EXR files (heights as stored: Y, a single channel, or the luminance of R, G and B), relative to the scene file",
            path.display(),
            dir.join("h.exr").display()
        )
    );
}

#[test]
fn check_of_a_directory_says_it_is_a_directory() {
    let dir = crate::common::scratch_dir("ron-syntax-check-dir");
    let out = crate::common::run_in(&dir, &["check", "."]);
    assert!(!out.status.success());
    assert_eq!(
        String::from_utf8_lossy(&out.stderr)
            .lines()
            .take(2)
            .collect::<Vec<_>>(),
        [
            ".:1:1: error: this is a directory, not a scene file",
            "  help: give a scene file; known scene formats: .ron, .rib, .gltf, .glb, .mi",
        ]
    );
}

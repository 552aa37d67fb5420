//! How each call-like value is written, for messages when a scene writes it the other way:
//! some shader nodes take their inputs in order (`Channel(Uv, 1)`), the others and every
//! variant with a `file` take named fields (`Mix(a: …, b: …, t: …)`, `Obj(file: "x.obj")`).
//! `docs/scene-format.md`'s node table writes each node in exactly the form given here.

/// Nodes that take their inputs in order, each with its form.
pub const POSITIONAL_NODES: &[(&str, &str)] = &[
    ("Add", "Add(<a>, <b>)"),
    ("Sub", "Sub(<a>, <b>)"),
    ("Mul", "Mul(<a>, <b>)"),
    ("Channel", "Channel(<colour>, <channel index>)"),
    ("Luminance", "Luminance(<colour>)"),
    ("Combine", "Combine(<r>, <g>, <b>)"),
    (
        "Graph",
        "Graph(\"<phenomenon>\", {\"<parameter>\": <input>, …})",
    ),
    ("Param", "Param(\"<parameter>\")"),
];

/// Nodes whose inputs are named, each with its form (as the node table of
/// `docs/scene-format.md` writes it: fields with defaults show them).
const NAMED_NODES: &[(&str, &str)] = &[
    ("Checker", "Checker(uv: Uv, scale: 2, a: 1, b: 0)"),
    (
        "Disk",
        "Disk(uv: Uv, center: (0.5, 0.5), radius: 0.4, fuzz: 0, inside: (0, 0, 1), outside: (1, 0, 0))",
    ),
    ("Steps", "Steps(uv: Uv, steps: 4, fuzz: 0.05)"),
    ("Repeat", "Repeat(uv: Uv, scale: 10)"),
    ("Noise", "Noise(p: Position, frequency: 1, seed: 0)"),
    (
        "Fbm",
        "Fbm(p: Position, frequency: 1, octaves: 4, lacunarity: 2, gain: 0.5, seed: 0)",
    ),
    (
        "Turbulence",
        "Turbulence(p: Position, frequency: 1, octaves: 4, lacunarity: 2, gain: 0.5, seed: 0)",
    ),
    ("Mix", "Mix(a: …, b: …, t: …)"),
    ("Smoothstep", "Smoothstep(edge0: …, edge1: …, x: …)"),
    ("Convert", "Convert(input: …, from: Rgb, to: Rgb)"),
];

/// Variants whose first field is the `file` they read.
const FILE_VARIANTS: &[&str] = &["Obj", "Ply", "Gltf", "LatLong", "Image", "Alpha"];

/// The names of [`POSITIONAL_NODES`].
pub fn positional_names() -> Vec<&'static str> {
    POSITIONAL_NODES.iter().map(|(name, _)| *name).collect()
}

/// Whether shader node or file variant `name` takes named fields (so a value written
/// without a name inside its parentheses is a call in the wrong style).
pub fn takes_named_fields(name: &str) -> bool {
    NAMED_NODES.iter().any(|(n, _)| *n == name) || FILE_VARIANTS.contains(&name)
}

/// The message for `name(field: …)` where `name` takes its inputs in order.
pub fn named_instead_of_positional(name: &str) -> Option<(String, String)> {
    let (_, form) = POSITIONAL_NODES.iter().find(|(n, _)| *n == name)?;
    Some((
        format!("{name} takes its inputs in order: {form}"),
        "write the inputs without names, in that order".into(),
    ))
}

/// The message for `name(value, …)` where `name` takes named fields; `first` is the text
/// of the first value written (a string is shown as the `file` of a file variant).
pub fn positional_instead_of_named(name: &str, first: &str) -> (String, String) {
    let help = format!(
        "write each field as `name: value`; docs/scene-format.md lists the fields of {name}"
    );
    if let Some((_, form)) = NAMED_NODES.iter().find(|(n, _)| *n == name) {
        return (format!("{name} takes named inputs: {form}"), help);
    }
    let form = if FILE_VARIANTS.contains(&name) && first.starts_with('"') {
        format!("{name}(file: {first})")
    } else if FILE_VARIANTS.contains(&name) {
        format!("{name}(file: \"…\")")
    } else {
        format!("{name}(<field>: <value>, …)")
    };
    (format!("{name} takes named fields: {form}"), help)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_node_table_of_the_docs_writes_every_form() {
        let docs = include_str!("../../../docs/scene-format.md");
        for (name, form) in POSITIONAL_NODES.iter().chain(NAMED_NODES) {
            assert!(docs.contains(&format!("`{form}`")), "{name}: {form}");
        }
    }

    #[test]
    fn forms_name_the_node_and_a_file() {
        assert_eq!(
            named_instead_of_positional("Luminance").unwrap().0,
            "Luminance takes its inputs in order: Luminance(<colour>)"
        );
        assert_eq!(named_instead_of_positional("Mix"), None);
        assert_eq!(
            positional_instead_of_named("Obj", "\"x.obj\"").0,
            "Obj takes named fields: Obj(file: \"x.obj\")"
        );
        assert_eq!(
            positional_instead_of_named("Sphere", "1").0,
            "Sphere takes named fields: Sphere(<field>: <value>, …)"
        );
    }
}

//! Issue 18, family 10: the format reference cannot drift. Every field and variant the RON
//! reader accepts (read from the `Deserialize` description types of every file of
//! `src/scene/` that declares one) is documented in `docs/scene-format.md` **where its type
//! is**: a struct's fields are rows of its field table (the table in its section that names
//! most of them) or, without one, words of its section; an enum's variants are words of its
//! section; and a table row that lists a field's alternatives (`` `A(…)` \| `B(…)` ``) lists
//! every variant of the field's enum.

use std::collections::BTreeMap;
use std::path::Path;

/// One `Deserialize` type of a description file.
struct DescType {
    /// Rust name (`CameraDesc`).
    name: String,
    is_enum: bool,
    untagged: bool,
    /// Fields and variants as written in a scene file, with a field's Rust type.
    members: Vec<Member>,
}

struct Member {
    name: String,
    is_field: bool,
    /// A field's Rust type text (`Option<ContourDesc>,`); empty for variants.
    ty: String,
}

fn rename_in(line: &str) -> Option<String> {
    line.split("rename = \"")
        .nth(1)
        .and_then(|r| r.split('"').next())
        .map(str::to_string)
}

/// Every `Deserialize` struct and enum in `source`, with its fields and variants (renames
/// applied; skipped fields left out; untagged enums have no written variant names).
fn desc_types(source: &str) -> Vec<DescType> {
    let mut out = Vec::new();
    let lines: Vec<&str> = source.lines().collect();
    let mut i = 0;
    while i < lines.len() {
        if !(lines[i].starts_with("#[derive(") && lines[i].contains("Deserialize")) {
            i += 1;
            continue;
        }
        let mut untagged = false;
        let mut j = i + 1;
        while lines[j].starts_with("#[") {
            untagged |= lines[j].contains("untagged");
            j += 1;
        }
        let head = lines[j].trim();
        let is_enum = head.starts_with("pub enum ");
        let name: String = head
            .split_whitespace()
            .nth(2)
            .unwrap_or_default()
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        let mut members = Vec::new();
        let mut depth = 0i32;
        // Open parentheses of code lines: the lines inside a tuple variant written over
        // several lines (`Graph(\n String,\n …\n),`) are its fields, not variants.
        let mut parens = 0i32;
        let mut rename: Option<String> = None;
        let mut skip = false;
        for line in &lines[j..] {
            let t = line.trim();
            let depth_here = depth;
            if depth_here == 0 && t.ends_with(';') {
                break;
            }
            depth += t.matches('{').count() as i32 - t.matches('}').count() as i32;
            if t.starts_with("#[serde(") {
                rename = rename_in(t).or(rename);
                skip |= t.contains("skip");
                continue;
            }
            if t.starts_with("//") || t.starts_with("#[") {
                continue;
            }
            let parens_here = parens;
            parens += t.matches('(').count() as i32 - t.matches(')').count() as i32;
            let body = t.trim_start_matches("pub ");
            let ident: String = body
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            let field =
                depth_here >= 1 && !ident.is_empty() && body[ident.len()..].starts_with(':');
            let variant = is_enum
                && depth_here == 1
                && parens_here == 0
                && ident.chars().next().is_some_and(char::is_uppercase)
                && !untagged;
            if (field || variant) && !skip {
                members.push(Member {
                    name: rename.take().unwrap_or_else(|| ident.clone()),
                    is_field: field,
                    ty: if field {
                        body[ident.len() + 1..].to_string()
                    } else {
                        String::new()
                    },
                });
            }
            rename = None;
            skip = false;
            if depth <= 0 && depth_here > 0 {
                break;
            }
        }
        out.push(DescType {
            name,
            is_enum,
            untagged,
            members,
        });
        i = j + 1;
    }
    out
}

/// The heading of the section documenting a type, for types whose section is not headed
/// by their own scene name in backticks (`` ## `Camera` ``).
const SECTION_OF: &[(&str, &str)] = &[
    ("Lens", "Lens shaders"),
    ("Volume", "Volume shaders"),
    ("Contour", "Contours"),
    ("Contours", "Contours"),
    ("Contrast", "Contours"),
    ("Approximation", "Approximation"),
    ("Space", "Approximation"),
    ("Displacement", "Displacement"),
    ("DisplacementMode", "Displacement"),
    ("Scalar", "Displacement"),
    ("Axis", "Displacement"),
    ("Diagnostic", "Diagnostic modes"),
    ("GridSpace", "Diagnostic modes"),
    ("PhotonQuantity", "Diagnostic modes"),
    ("BvhQuantity", "Diagnostic modes"),
    ("Feature", "Feature switches"),
    ("Progressive", "Progressive photon mapping"),
    ("PhotonDepth", "Photon trace depth"),
    ("PhotonFilter", "Filters"),
    ("PhotonMapFile", "Photon map files"),
    ("PhotonMap", "Photon maps: caustics and global illumination"),
    ("Integrator", "Integrators and trace depths"),
    ("Shadow", "Material shadow and environment shaders"),
    (
        "MaterialEnvironment",
        "Material shadow and environment shaders",
    ),
    ("Input", "Shader graphs"),
    ("Node", "Shader graphs"),
    ("Phenomenon", "Shader graphs"),
    ("Bump", "Shader graphs"),
    ("Wrap", "Shader graphs"),
    ("AxisWrap", "Shader graphs"),
    ("Encoding", "Shader graphs"),
    ("ColourSpace", "Shader graphs"),
    ("Basis", "Free-form surfaces"),
    ("Mesh", "`Object`"),
    ("Shader", "`Material`"),
    ("LocalLobe", "`Material`"),
    ("EnvironmentShader", "`Environment`"),
    ("DepthExceeded", "`Environment`"),
    ("LightKind", "`Light`"),
    ("Placement", "`Camera`"),
    ("ToneMap", "`Imager`"),
    ("ImagerPattern", "`Imager`"),
    ("Pass", "`Output`"),
    ("Format", "`Output`"),
    ("Transform", "`Instance`"),
    ("Filter", "`Options`"),
    ("Face", "`Options`"),
    ("BvhQuality", "`Options`"),
    ("Uvs", "`Bake`"),
    ("BakeOutput", "`Bake`"),
    ("BakeKind", "`Bake`"),
    ("Denoise", "`Bake`"),
    ("BakeTarget", "`Bake`"),
    ("LightmapStore", "`Bake`"),
    ("NormalSpace", "`Bake`"),
    ("BakeFormat", "`Bake`"),
];

/// The markdown as headings with their line ranges.
struct Doc<'a> {
    lines: Vec<&'a str>,
    /// (line, level, text) of every heading.
    headings: Vec<(usize, usize, &'a str)>,
}

impl<'a> Doc<'a> {
    fn new(text: &'a str) -> Self {
        let lines: Vec<&str> = text.lines().collect();
        let mut fenced = false;
        let mut headings = Vec::new();
        for (i, l) in lines.iter().enumerate() {
            if l.trim_start().starts_with("```") {
                fenced = !fenced;
            }
            if !fenced && l.starts_with('#') {
                let level = l.chars().take_while(|&c| c == '#').count();
                headings.push((i, level, l[level..].trim()));
            }
        }
        Doc { lines, headings }
    }

    /// The section headed `heading`: its own lines (to the next heading) and its lines
    /// with subsections.
    fn section(&self, heading: &str) -> Option<(usize, &[&'a str], &[&'a str])> {
        let k = self.headings.iter().position(|h| h.2 == heading)?;
        let (start, level, _) = self.headings[k];
        let rest = &self.headings[k + 1..];
        let own_end = rest.first().map_or(self.lines.len(), |h| h.0);
        let end = rest
            .iter()
            .find(|h| h.1 <= level)
            .map_or(self.lines.len(), |h| h.0);
        Some((
            start + 1,
            &self.lines[start..own_end],
            &self.lines[start..end],
        ))
    }
}

/// Identifiers inside `` `…` `` spans and fenced blocks.
fn code_words(lines: &[&str]) -> Vec<String> {
    let mut code = String::new();
    let mut fenced = false;
    for line in lines {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        if fenced {
            code.push_str(line);
            code.push('\n');
        } else {
            for (k, span) in line.split('`').enumerate() {
                if k % 2 == 1 {
                    code.push_str(span);
                    code.push('\n');
                }
            }
        }
    }
    let mut words: Vec<String> = code
        .split(|c: char| !(c.is_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .map(str::to_string)
        .collect();
    words.sort();
    words.dedup();
    words
}

/// The tables of `lines`: for each, its rows by the names in their first cell, with the
/// second cell (the type).
fn tables(lines: &[&str]) -> Vec<BTreeMap<String, String>> {
    let mut out = Vec::new();
    let mut current: Option<BTreeMap<String, String>> = None;
    for line in lines {
        if !line.starts_with('|') {
            out.extend(current.take());
            continue;
        }
        let rows = current.get_or_insert_with(BTreeMap::new);
        let cells: Vec<&str> = line.split(" | ").collect();
        let first = cells[0].trim_start_matches('|');
        let second = cells.get(1).copied().unwrap_or_default().to_string();
        for (k, name) in first.split('`').enumerate() {
            if k % 2 == 1 {
                rows.entry(name.to_string())
                    .or_insert_with(|| second.clone());
            }
        }
    }
    out.extend(current);
    out
}

/// The variant names a table cell lists as alternatives: `` `A(…)` \| `B` `` → A, B.
fn alternatives(cell: &str) -> Vec<String> {
    if !cell.contains("\\|") {
        return Vec::new();
    }
    cell.split('`')
        .enumerate()
        .filter(|(k, _)| k % 2 == 1)
        .map(|(_, span)| {
            span.chars()
                .take_while(|c| c.is_alphanumeric())
                .collect::<String>()
        })
        .filter(|w| w.chars().next().is_some_and(char::is_uppercase))
        .collect()
}

/// Every problem of `docs` against `types` (file name, type).
fn problems(docs: &str, types: &[(String, DescType)]) -> Vec<String> {
    let doc = Doc::new(docs);
    let all_words = code_words(&doc.lines);
    let enums: BTreeMap<&str, &DescType> = types
        .iter()
        .filter(|(_, t)| t.is_enum && !t.untagged)
        .map(|(_, t)| (t.name.as_str(), t))
        .collect();
    let mut found = Vec::new();
    for (file, t) in types {
        let short = t.name.trim_end_matches("Desc");
        let heading = SECTION_OF
            .iter()
            .find(|(n, _)| *n == short)
            .map_or_else(|| format!("`{short}`"), |(_, h)| (*h).to_string());
        let Some((line, own, whole)) = doc.section(&heading) else {
            for m in &t.members {
                if !all_words.contains(&m.name) {
                    found.push(format!(
                        "{file}: {}.{} is not in the document",
                        t.name, m.name
                    ));
                }
            }
            continue;
        };
        let fields: Vec<&Member> = t.members.iter().filter(|m| m.is_field).collect();
        let table = tables(own)
            .into_iter()
            .max_by_key(|rows| fields.iter().filter(|f| rows.contains_key(&f.name)).count())
            .filter(|rows| {
                let n = fields.iter().filter(|f| rows.contains_key(&f.name)).count();
                !t.is_enum && n >= 2 && 2 * n >= fields.len()
            });
        let words = code_words(whole);
        for m in &t.members {
            match (&table, m.is_field) {
                (Some(rows), true) => match rows.get(&m.name) {
                    None => found.push(format!(
                        "{file}: {}.{} has no row in the table of {heading} (line {line})",
                        t.name, m.name
                    )),
                    Some(cell) => {
                        let listed = alternatives(cell);
                        let ty_words =
                            m.ty.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                                .filter_map(|w| enums.get(w));
                        for e in ty_words {
                            let variants: Vec<&str> = e
                                .members
                                .iter()
                                .filter(|v| !v.is_field)
                                .map(|v| v.name.as_str())
                                .collect();
                            if !listed.iter().any(|a| variants.contains(&a.as_str())) {
                                continue;
                            }
                            for v in variants.iter().filter(|v| !listed.iter().any(|a| a == *v)) {
                                found.push(format!(
                                    "{file}: {}::{v} is missing from the `{}` row of {heading} (line {line})",
                                    e.name, m.name
                                ));
                            }
                        }
                    }
                },
                _ => {
                    if !words.contains(&m.name) {
                        found.push(format!(
                            "{file}: {}.{} is not in the section {heading} (line {line})",
                            t.name, m.name
                        ));
                    }
                }
            }
        }
    }
    found
}

/// Every description type of `src/scene/`, with the file it is in.
fn scene_desc_types(root: &Path) -> Vec<(String, DescType)> {
    let mut files: Vec<_> = std::fs::read_dir(root.join("src/scene"))
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .collect();
    files.sort();
    let mut out = Vec::new();
    for path in files {
        let source = std::fs::read_to_string(&path).unwrap();
        let file = path.file_name().unwrap().to_string_lossy().into_owned();
        out.extend(desc_types(&source).into_iter().map(|t| (file.clone(), t)));
    }
    out
}

#[test]
fn every_accepted_field_and_variant_is_in_the_format_reference_where_its_type_is() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let docs = std::fs::read_to_string(root.join("docs/scene-format.md")).unwrap();
    let types = scene_desc_types(root);
    let files: std::collections::BTreeSet<&str> = types.iter().map(|(f, _)| f.as_str()).collect();
    for file in [
        "desc_diagnostic.rs",
        "desc_photon_depth.rs",
        "nodes_desc.rs",
        "desc.rs",
    ] {
        assert!(files.contains(file), "{file} was not scanned: {files:?}");
    }
    let names: usize = types.iter().map(|(_, t)| t.members.len()).sum();
    assert!(
        types.len() > 60 && names > 300,
        "the scan found {} types, {names} names",
        types.len()
    );
    let found = problems(&docs, &types);
    assert!(
        found.is_empty(),
        "docs/scene-format.md:\n{}",
        found.join("\n")
    );
}

/// The gaps this test let through before it checked names where their type is documented:
/// a Camera table without the `imager` row, and a Material `contour` row listing five of
/// the seven contour shaders.
#[test]
fn a_missing_table_row_or_alternative_is_caught() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let docs = std::fs::read_to_string(root.join("docs/scene-format.md")).unwrap();
    let types = scene_desc_types(root);
    let imager_row = docs
        .lines()
        .find(|l| l.starts_with("| `imager` |"))
        .expect("the Camera table has an imager row");
    let old = docs
        .replace(&format!("{imager_row}\n"), "")
        .replace(" \\| `Silhouette(…)`", "")
        .replace(" \\| `Layered(…)`", "");
    let found = problems(&old, &types);
    let line = docs.lines().position(|l| l == "## `Camera`").unwrap() + 1;
    // 1-based in the edited text, which is one line shorter above it.
    let material = docs.lines().position(|l| l == "## `Material`").unwrap();
    assert_eq!(
        found,
        [
            format!("desc.rs: CameraDesc.imager has no row in the table of `Camera` (line {line})"),
            format!("desc.rs: ContourDesc::Silhouette is missing from the `contour` row of `Material` (line {material})"),
            format!("desc.rs: ContourDesc::Layered is missing from the `contour` row of `Material` (line {material})"),
        ]
    );
}

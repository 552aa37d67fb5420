//! Issue 18, family 10: the format reference cannot drift. Every field and variant the RON
//! reader accepts (read from the `Deserialize` description types in `src/scene/desc*.rs` and
//! `nodes_desc.rs`) is named in `docs/scene-format.md`.

use std::path::Path;

/// Field and variant names of every `Deserialize` struct and enum in `source`, as written in
/// a scene file (renames applied; untagged enums have no written variant names).
fn accepted_names(source: &str) -> Vec<(String, String)> {
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
        let type_name = head
            .split_whitespace()
            .nth(2)
            .unwrap_or_default()
            .trim_end_matches('{')
            .to_string();
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
                if let Some(r) = t.split("rename = \"").nth(1) {
                    rename = r.split('"').next().map(str::to_string);
                }
                skip |= t.contains("skip");
                continue;
            }
            if t.starts_with("///") || t.starts_with("//") || t.starts_with("#[") {
                continue;
            }
            let parens_here = parens;
            parens += t.matches('(').count() as i32 - t.matches(')').count() as i32;
            let ident: String = t
                .trim_start_matches("pub ")
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            let field = depth_here >= 1
                && !ident.is_empty()
                && t.trim_start_matches("pub ")[ident.len()..].starts_with(':');
            let variant = is_enum
                && depth_here == 1
                && parens_here == 0
                && ident.chars().next().is_some_and(char::is_uppercase)
                && !untagged;
            if (field || variant) && !skip {
                out.push((type_name.clone(), rename.take().unwrap_or(ident)));
            }
            rename = None;
            skip = false;
            if depth <= 0 && depth_here > 0 {
                break;
            }
        }
        i = j + 1;
    }
    out
}

/// Every identifier written in code (`` `…` `` spans and fenced blocks) of a markdown text.
fn code_words(markdown: &str) -> Vec<String> {
    let mut code = String::new();
    let mut fenced = false;
    for line in markdown.lines() {
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

#[test]
fn every_accepted_field_and_variant_is_in_the_format_reference() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let docs = std::fs::read_to_string(root.join("docs/scene-format.md")).unwrap();
    let in_code = code_words(&docs);
    let mut missing = Vec::new();
    let mut seen = 0;
    for file in [
        "src/scene/desc.rs",
        "src/scene/desc_camera.rs",
        "src/scene/desc_contour.rs",
        "src/scene/desc_environment.rs",
        "src/scene/desc_geometry.rs",
        "src/scene/desc_material_shaders.rs",
        "src/scene/nodes_desc.rs",
    ] {
        let source = std::fs::read_to_string(root.join(file)).unwrap();
        for (ty, name) in accepted_names(&source) {
            seen += 1;
            if !in_code.contains(&name) {
                missing.push(format!("{file}: {ty}.{name}"));
            }
        }
    }
    assert!(seen > 150, "the scan found only {seen} names");
    assert!(
        missing.is_empty(),
        "not in docs/scene-format.md:\n{}",
        missing.join("\n")
    );
}

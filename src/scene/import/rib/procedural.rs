//! `Procedural` (RISpec 3.2 §5.7) and PRMan's `Procedural2`: geometry made when the
//! renderer reaches it.
//!
//! `Procedural "DelayedReadArchive" ["file.rib"] [xmin xmax ymin ymax zmin zmax]` is a
//! `ReadArchive` of the file that a RenderMan renderer postpones until the bound is on
//! screen; the bound only culls, so reading the file where the request stands, with the
//! attributes and transformation current there, makes the same image. The arguments are
//! checked first: a string array of one file name and a bound of six numbers, each a located
//! error otherwise. `RunProgram` and `DynamicLoad` run code the reader does not run, and
//! `Procedural2` calls PRMan's plug-ins: each is a located warning that the geometry it would
//! make is missing, with what to do instead.

use super::super::located::{Pos, Problem};
use super::params::Args;
use super::parse::{Request, Value};
use crate::scene::suggest::suggestion;

/// RISpec 3.2's procedurals in RIB, in the order the help lists them.
const PROCEDURALS: &[&str] = &["DelayedReadArchive", "RunProgram", "DynamicLoad"];

/// The form the help shows.
const FORM: &str =
    "Procedural \"DelayedReadArchive\" [\"file.rib\"] [xmin xmax ymin ymax zmin zmax]";

/// What a `Procedural` or `Procedural2` request asks of the reader.
#[derive(Debug, PartialEq)]
pub enum ProceduralCall {
    /// Read this archive file (as written) here; the position is its file-name string.
    Archive { file: String, pos: Pos },
    /// Nothing to read: the warning that says what is missing.
    Missing(Problem),
}

/// Reads `Procedural`'s arguments (`a` at the first).
pub fn read(r: &Request, a: &mut Args<'_>) -> Result<ProceduralCall, Problem> {
    if r.name == "Procedural2" {
        return Ok(ProceduralCall::Missing(procedural2(r)));
    }
    let (name, npos) = a.string("procedure name")?;
    if name != "DelayedReadArchive" {
        return Ok(ProceduralCall::Missing(unsupported(&name, npos)));
    }
    let what = "Procedural \"DelayedReadArchive\"";
    let args = a.any("file name")?;
    let file = match &args.value {
        Value::Str(s) => (s.clone(), args.pos),
        v => match v.strs() {
            Some([one]) => (one.clone(), args.item(0)),
            Some(names) => {
                return Err(Problem::error(
                    args.pos,
                    format!("{what} takes 1 file name, found {}", names.len()),
                )
                .with_help(format!("write it as {FORM}")));
            }
            None => {
                return Err(Problem::error(
                    args.pos,
                    format!(
                        "expected an array of strings for the file name of {what}, found {}",
                        v.kind()
                    ),
                )
                .with_help(format!("write it as {FORM}")));
            }
        },
    };
    if a.done() {
        return Err(Problem::error(
            r.pos,
            format!("{what} needs a bound (6 numbers: xmin xmax ymin ymax zmin zmax)"),
        )
        .with_help(format!("write it as {FORM}")));
    }
    let bound = a.any("bound")?;
    let count = match &bound.value {
        Value::Nums(v) => v.len(),
        Value::Num(_) => 1,
        v => {
            return Err(Problem::error(
                bound.pos,
                format!(
                    "expected 6 numbers for the bound of {what}, found {}",
                    v.kind()
                ),
            )
            .with_help(format!("write it as {FORM}")));
        }
    };
    if count != 6 {
        return Err(Problem::error(
            bound.pos,
            format!(
                "the bound of {what} takes 6 numbers (xmin xmax ymin ymax zmin zmax), found {count}"
            ),
        ));
    }
    Ok(ProceduralCall::Archive {
        file: file.0,
        pos: file.1,
    })
}

/// The warning for `Procedural "RunProgram"`, `"DynamicLoad"` or an unknown procedure.
fn unsupported(name: &str, pos: Pos) -> Problem {
    let (why, help) = match name {
        "RunProgram" => (
            "stagelight runs no programs: the geometry it would make is missing",
            Some(
                "run the program yourself, save the RIB it writes and read that with \
                 ReadArchive"
                    .to_string(),
            ),
        ),
        "DynamicLoad" => (
            "stagelight loads no plug-ins: the geometry it would make is missing",
            Some(
                "have the plug-in's renderer write the geometry as RIB and read that with \
                 ReadArchive"
                    .to_string(),
            ),
        ),
        _ => (
            "not one of RenderMan's procedurals: the geometry it would make is missing",
            suggestion(name, PROCEDURALS, "procedurals"),
        ),
    };
    let mut w = Problem::warning(pos, format!("ignored Procedural \"{name}\": {why}"));
    w.help = help;
    w
}

/// The warning for PRMan's `Procedural2`, at its plug-in's name (its arguments are the
/// plug-in's and are not read).
fn procedural2(r: &Request) -> Problem {
    let plugin = r.args.first().and_then(|a| match &a.value {
        Value::Str(s) => Some((s.as_str(), a.pos)),
        _ => None,
    });
    let (name, pos) = plugin.unwrap_or(("", r.pos));
    let called = if name.is_empty() {
        "Procedural2".to_string()
    } else {
        format!("Procedural2 \"{name}\"")
    };
    Problem::warning(
        pos,
        format!(
            "ignored {called}: stagelight loads no plug-ins: the geometry it would make is missing"
        ),
    )
    .with_help(
        "for Procedural2 \"DelayedReadArchive2\", read its file with ReadArchive \"file.rib\" \
         (or Procedural \"DelayedReadArchive\")",
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::import::rib::{lexer, parse};

    fn call(text: &str) -> Result<ProceduralCall, Problem> {
        let (tokens, _) = lexer::tokens(text);
        let (requests, _) = parse::requests(&tokens);
        let r = &requests[0];
        let mut a = Args::new(r);
        read(r, &mut a)
    }

    #[test]
    fn delayed_read_archive_reads_its_file_at_the_name() {
        assert_eq!(
            call("Procedural \"DelayedReadArchive\" [\"a.rib\"] [-1 1 -1 1 -1 1]"),
            Ok(ProceduralCall::Archive {
                file: "a.rib".into(),
                pos: Pos {
                    line: 1,
                    column: 34
                }
            })
        );
    }

    #[test]
    fn unknown_procedurals_get_the_closest_name() {
        let Ok(ProceduralCall::Missing(w)) =
            call("Procedural \"DelayedReadArchiv\" [\"a.rib\"] [-1 1 -1 1 -1 1]")
        else {
            panic!()
        };
        assert_eq!(
            w.help.as_deref(),
            Some("did you mean \"DelayedReadArchive\"?")
        );
    }
}

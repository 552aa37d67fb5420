//! Paths on `#SBATCH` lines, written the way sbatch reads them back.
//!
//! sbatch splits a directive line into arguments itself (`get_argument` in Slurm's
//! `src/sbatch/opt.c`): at whitespace, with `'…'` and `"…"` grouping characters (whitespace
//! and `#` included), a backslash taking the next character literally (inside quotes too),
//! and an unquoted `#` starting a comment that ends the line's arguments. A line ends at its
//! newline, so no argument can hold one. `--output` is moreover a filename pattern
//! (`expand_stdio_fields` in `src/common/print_fields.c`): `%a`, `%j`, … are replaced and
//! `%%` is one `%`, and a pattern holding a backslash has every backslash dropped and no
//! `%` replaced — so a log path with a backslash cannot be named at all.

use std::path::Path;

/// `value` as one argument of an `#SBATCH` line: as it is when sbatch would read it back
/// unchanged, else in double quotes with `"` and `\` escaped. `value` must hold no newline
/// ([`refusal`] refuses such paths before any script is written).
pub fn word(value: &str) -> String {
    let plain = !value.is_empty()
        && !value
            .chars()
            .any(|c| c.is_whitespace() || matches!(c, '"' | '\'' | '\\' | '#'));
    if plain {
        return value.to_string();
    }
    let mut quoted = String::with_capacity(value.len() + 2);
    quoted.push('"');
    for c in value.chars() {
        if matches!(c, '"' | '\\') {
            quoted.push('\\');
        }
        quoted.push(c);
    }
    quoted.push('"');
    quoted
}

/// `dir/name` as an `--output` filename pattern whose `name` may hold Slurm's replacement
/// symbols (`part_%a.log`): every `%` of `dir` doubled so that Slurm keeps it.
pub fn log_pattern(dir: &Path, name: &str) -> String {
    format!("{}/{name}", dir.to_string_lossy().replace('%', "%%"))
}

/// Why a farm job whose logs go to `logs` and whose jobs run in `workdir` cannot be written
/// as `#SBATCH` lines (`None` when it can): a line break in either path, a backslash in the
/// log directory, or a path that is not UTF-8 (a script is text). The message ends with a
/// `help:` line.
pub fn refusal(logs: &Path, workdir: &Path) -> Option<String> {
    let shown = |p: &Path| p.to_string_lossy().escape_debug().to_string();
    let out_help = "give --out a directory whose path has no line break or backslash";
    let (Some(log_text), Some(work_text)) = (logs.to_str(), workdir.to_str()) else {
        let (what, path) = if logs.to_str().is_none() {
            ("--out", logs)
        } else {
            ("the working directory", workdir)
        };
        return Some(format!(
            "{what} {} is not valid UTF-8, so the batch scripts cannot name it\n  help: use a directory whose path is UTF-8",
            shown(path)
        ));
    };
    if work_text.contains(['\n', '\r']) {
        return Some(format!(
            "the working directory \"{}\" has a line break, which the `#SBATCH --chdir` line cannot hold (sbatch reads a directive up to the line's end)\n  help: run farm from a directory whose path has no line break",
            shown(workdir)
        ));
    }
    if log_text.contains(['\n', '\r']) {
        return Some(format!(
            "the log directory \"{}\" has a line break, which the `#SBATCH --output` line cannot hold (sbatch reads a directive up to the line's end)\n  help: {out_help}",
            shown(logs)
        ));
    }
    if log_text.contains('\\') {
        return Some(format!(
            "the log directory \"{}\" has a backslash: Slurm drops every backslash of an `--output` path (and then replaces no %a), so the jobs' logs would go elsewhere\n  help: {out_help}",
            shown(logs)
        ));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// sbatch's `get_argument`, transcribed: the arguments of one directive line.
    fn sbatch_arguments(line: &str) -> Vec<String> {
        let mut args = Vec::new();
        let mut chars = line.chars().peekable();
        loop {
            while chars.peek().is_some_and(|c| c.is_whitespace()) {
                chars.next();
            }
            if chars.peek().is_none() {
                return args;
            }
            let (mut arg, mut quote, mut any) = (String::new(), None, false);
            while let Some(&c) = chars.peek() {
                if quote.is_none() && c.is_whitespace() {
                    break;
                }
                chars.next();
                match (c, quote) {
                    ('\\', _) => {
                        if let Some(next) = chars.next() {
                            arg.push(next);
                        }
                    }
                    (c, Some(q)) if c == q => quote = None,
                    (c, Some(_)) => arg.push(c),
                    ('"' | '\'', None) => quote = Some(c),
                    ('#', None) => {
                        if any || !arg.is_empty() {
                            args.push(arg);
                        }
                        return args;
                    }
                    (c, None) => arg.push(c),
                }
                any = true;
            }
            assert!(quote.is_none(), "unmatched quote in {line}");
            args.push(arg);
        }
    }

    #[test]
    fn awkward_paths_read_back_as_one_argument() {
        for dir in [
            "/proj/My Show",
            "/proj/shot#12",
            "/proj/it's",
            "/proj/say \"hi\"",
            "/proj/a\\b",
            "/proj/tab\there",
            "/plain/dir",
        ] {
            let line = format!(" --chdir={}", word(dir));
            assert_eq!(
                sbatch_arguments(&line),
                [format!("--chdir={dir}")],
                "{line}"
            );
        }
        assert_eq!(word("/plain/dir"), "/plain/dir");
        assert_eq!(word("/proj/My Show"), "\"/proj/My Show\"");
        assert_eq!(word("/proj/a\\b \"c\""), "\"/proj/a\\\\b \\\"c\\\"\"");
    }

    #[test]
    fn a_percent_of_the_directory_is_kept_and_the_array_index_replaced() {
        assert_eq!(
            log_pattern(Path::new("/r/100% done/logs"), "part_%a.log"),
            "/r/100%% done/logs/part_%a.log"
        );
    }

    #[test]
    fn line_breaks_and_backslashes_in_the_log_directory_are_refused() {
        let work = Path::new("/work");
        assert!(refusal(Path::new("/a b/logs"), work).is_none());
        let r = refusal(Path::new("/a\nb/logs"), work).unwrap();
        assert!(
            r.starts_with("the log directory \"/a\\nb/logs\" has a line break"),
            "{r}"
        );
        let r = refusal(Path::new("/a\\b/logs"), work).unwrap();
        assert!(r.contains("has a backslash"), "{r}");
        let r = refusal(Path::new("/x/logs"), Path::new("/w\nx")).unwrap();
        assert!(r.starts_with("the working directory"), "{r}");
        assert!(refusal(Path::new("/x/logs"), Path::new("/w\\x")).is_none());
    }
}

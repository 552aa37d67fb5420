//! Output paths that would overwrite an input or each other (issue 18, family 5), or that
//! cannot be written ([`super::writable`]), refused before anything runs: `check` and every
//! command that writes files run the same test.
//!
//! The inputs are the scene file, its includes and every file a scene names outside its
//! outputs (meshes, textures, environment maps, displacement maps); the outputs are the
//! render camera's files (after `-o`), the bake files of every request (in the bake
//! directory), a bake part's file (`bake --part`), the glTF copy of `--write-gltf` (`bake`,
//! `merge` of bake parts, and `farm --bake`'s merge job, checked by `farm`) and
//! `--stats-json`. Two paths are the same file when they name the same
//! directory entry: both are compared absolute, through the real (symlink-free) parent
//! directory where it exists.

use std::path::{Component, Path, PathBuf};

use hecs::World;

use crate::components::{BakeRequest, Camera, Name, OutputLinks, RenderCamera, SourceLink};
use crate::frame::RunInputs;

/// Who asked for an output file: a command-line flag or a scene element.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Origin {
    /// A flag (`-o`, `--stats-json`).
    Flag(&'static str),
    /// A scene element (its `file:line:column` and what it is, e.g. `camera "cam" output 2`).
    Scene(SourceLink, String),
}

/// One file the run would write.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlannedOutput {
    /// The destination as the run will write it.
    pub path: PathBuf,
    /// Who asked for it.
    pub origin: Origin,
    /// Whether the run surely writes it, so that its directory must take it: not a photon
    /// map file that is there (a run may only read it), nor a camera output of a part run
    /// (which writes its part file instead; the merge writes the outputs).
    pub surely_written: bool,
}

/// A refused output: the text printed (located for scene elements) and whether a flag takes
/// part in it (a usage error, exit 2: `-o` or `--stats-json` is the output, or the earlier
/// output it clashes with) or only the scene (exit 1).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Clash {
    /// The complete message, `file:line:col: error: …` or `error: …`, with a `help:` line.
    pub text: String,
    /// True when a command-line flag names the refused output or the one it clashes with.
    pub usage: bool,
}

/// The files a run with `inputs` writes for `world`, `stats_json` last.
pub fn planned_outputs(
    world: &World,
    inputs: &RunInputs,
    stats_json: Option<&Path>,
) -> Vec<PlannedOutput> {
    let mut out = Vec::new();
    if inputs.tasks.bake {
        let mut requests: Vec<_> = world
            .query::<(hecs::Entity, &BakeRequest, Option<&SourceLink>)>()
            .iter()
            .map(|(e, r, l)| (e.to_bits(), r.clone(), l.cloned()))
            .collect();
        requests.sort_by_key(|(e, ..)| *e);
        for (_, request, link) in requests {
            for path in crate::bake::files::planned_paths(&request, &inputs.bake_dir) {
                out.push(PlannedOutput {
                    path,
                    origin: Origin::Scene(
                        link.clone().unwrap_or_else(unknown_link),
                        format!("bake request on instance \"{}\"", request.name),
                    ),
                    surely_written: true,
                });
            }
        }
    }
    if inputs.tasks.bake {
        out.extend(bake_run_files(inputs));
    }
    if inputs.tasks.render && !inputs.outputs.discard {
        out.extend(camera_outputs(world, inputs));
    }
    if let (true, None, Some(file)) = (
        inputs.tasks.render && inputs.settings.photons.any(),
        &inputs.photon_cache,
        &inputs.settings.photon_map,
    ) {
        out.push(PlannedOutput {
            path: file.path.clone(),
            origin: Origin::Scene(unknown_link(), "options photon_map file".to_string()),
            surely_written: !file.path.is_file(),
        });
    }
    if let Some(path) = stats_json {
        out.push(PlannedOutput {
            path: path.to_path_buf(),
            origin: Origin::Flag("--stats-json"),
            surely_written: true,
        });
    }
    out
}

/// The render camera's outputs after `-o`: the one `-o` names is the flag's, every other is
/// located at its `file` in the scene (at the camera where that is not known).
fn camera_outputs(world: &World, inputs: &RunInputs) -> Vec<PlannedOutput> {
    let mut query = world.query::<(
        &Camera,
        &RenderCamera,
        Option<&Name>,
        Option<&SourceLink>,
        Option<&OutputLinks>,
    )>();
    let Some((camera, _, name, link, links)) = query.iter().next() else {
        return Vec::new();
    };
    let name = name.map_or("?", |n| n.0.as_str());
    let applied = inputs.outputs.apply(&camera.outputs).unwrap_or_default();
    // A part run writes its part file (`-o`) instead of the camera's outputs.
    let part = inputs.part.is_some();
    applied
        .into_iter()
        .enumerate()
        .map(|(k, spec)| {
            // `-o` replaces one output in place, or is added after the camera's own.
            let flagged = inputs.outputs.first.as_ref() == Some(&spec.path)
                && camera.outputs.get(k) != Some(&spec);
            let origin = if flagged {
                Origin::Flag("-o")
            } else {
                let at = links.and_then(|l| l.0.get(k)).or(link);
                Origin::Scene(
                    at.cloned().unwrap_or_else(unknown_link),
                    format!("camera \"{name}\" output {}", k + 1),
                )
            };
            PlannedOutput {
                path: spec.path,
                origin,
                surely_written: flagged || !part,
            }
        })
        .collect()
}

/// The files a bake writes besides its requests' textures because of its flags: the part
/// file of `bake --part K/N` and the glTF copy of `--write-gltf` (`bake`, `merge` of bake
/// parts), both in the bake directory.
fn bake_run_files(inputs: &RunInputs) -> Vec<PlannedOutput> {
    let mut out = Vec::new();
    if let (Some(run), false) = (&inputs.part, inputs.tasks.render) {
        let name = crate::farm::bake_part::part_file_name(run.part.index, run.part.count);
        out.push(PlannedOutput {
            path: inputs.bake_dir.join(name),
            origin: Origin::Flag("--part"),
            surely_written: true,
        });
    }
    if let Some(source) = &inputs.write_gltf {
        out.push(PlannedOutput {
            path: crate::bake::gltf_out::baked_glb_path(source, &inputs.bake_dir),
            origin: Origin::Flag("--write-gltf"),
            surely_written: true,
        });
    }
    out
}

fn unknown_link() -> SourceLink {
    SourceLink {
        file: PathBuf::new(),
        line: 1,
        column: 1,
    }
}

/// The identity of a path for comparison: absolute, `.` and `..` resolved, through the real
/// parent directory when it exists.
pub fn same_file_key(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let mut clean = PathBuf::new();
    for c in absolute.components() {
        match c {
            Component::ParentDir => {
                clean.pop();
            }
            Component::CurDir => {}
            other => clean.push(other),
        }
    }
    if let Ok(real) = std::fs::canonicalize(&clean) {
        return real;
    }
    match (clean.parent(), clean.file_name()) {
        (Some(dir), Some(name)) => std::fs::canonicalize(dir)
            .map(|d| d.join(name))
            .unwrap_or(clean),
        _ => clean,
    }
}

/// Refuses every output that is an input or that an earlier output already writes; `scene`
/// is the scene file itself (also in `inputs`, not necessarily first: the MTL files of its
/// OBJ meshes come before it).
pub fn clashes(scene: &Path, inputs: &[PathBuf], outputs: &[PlannedOutput]) -> Vec<Clash> {
    let scene_key = same_file_key(scene);
    let input_keys: Vec<PathBuf> = inputs.iter().map(|p| same_file_key(p)).collect();
    let mut seen: Vec<(PathBuf, usize)> = Vec::new();
    let mut found = Vec::new();
    for (i, out) in outputs.iter().enumerate() {
        let key = same_file_key(&out.path);
        // A clash a flag takes part in is a usage error, whichever of the two it names.
        let mut flagged = matches!(out.origin, Origin::Flag(_));
        let problem = if let Some(k) = input_keys.iter().position(|k| *k == key) {
            let what = if input_keys[k] == scene_key {
                "the scene file"
            } else {
                "an input of the scene"
            };
            Some(format!(
                "{} would overwrite {what} {}",
                describe(out),
                inputs[k].display()
            ))
        } else if let Some((_, first)) = seen.iter().find(|(k, _)| *k == key) {
            flagged |= matches!(outputs[*first].origin, Origin::Flag(_));
            Some(format!(
                "{} is also written by {}",
                describe(out),
                describe(&outputs[*first])
            ))
        } else {
            None
        };
        seen.push((key, i));
        if let Some(message) = problem {
            let mut refused = clash(out, message);
            refused.usage = flagged;
            found.push(refused);
        }
    }
    found
}

/// `--stats-json out.png`, `camera "cam" output 2 ("a.png")`.
fn describe(out: &PlannedOutput) -> String {
    match &out.origin {
        Origin::Flag(flag) => format!("{flag} {}", out.path.display()),
        Origin::Scene(_, what) => format!("{what} (\"{}\")", out.path.display()),
    }
}

fn clash(out: &PlannedOutput, message: String) -> Clash {
    let help = "give every output its own file, and none the name of an input";
    refusal(out, format!("{message}\n  help: {help}"))
}

/// `text` (a message and its help line) as the refusal of `out`: located at the scene
/// element that names it, or a usage error of its flag.
pub(super) fn refusal(out: &PlannedOutput, text: String) -> Clash {
    match &out.origin {
        Origin::Flag(_) => Clash {
            text: format!("error: {text}"),
            usage: true,
        },
        Origin::Scene(link, _) => Clash {
            text: format!(
                "{}:{}:{}: error: {text}",
                link.file.display(),
                link.line,
                link.column
            ),
            usage: false,
        },
    }
}

/// Refuses every output the run surely writes whose path cannot be written
/// ([`super::writable`]): a directory, a path through a file, a directory that takes no new
/// file or cannot be created. Each directory is tried once.
pub fn unwritable(outputs: &[PlannedOutput]) -> Vec<Clash> {
    let mut tried: Vec<(PathBuf, Option<super::writable::PathProblem>)> = Vec::new();
    let mut found = Vec::new();
    for out in outputs.iter().filter(|o| o.surely_written) {
        let problem = if out.path.is_dir() {
            Some(super::writable::PathProblem::IsADirectory)
        } else {
            let dir = out
                .path
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
                .unwrap_or(Path::new("."))
                .to_path_buf();
            match tried.iter().find(|(d, _)| *d == dir) {
                Some((_, problem)) => problem.clone(),
                None => {
                    let problem = super::writable::dir_problem(&dir);
                    tried.push((dir, problem.clone()));
                    problem
                }
            }
        };
        if let Some(problem) = problem {
            found.push(refusal(out, problem.text(&describe(out))));
        }
    }
    found
}

/// Everything refused for a run of the scene at `scene`.
pub fn check(
    scene: &Path,
    world: &World,
    inputs: &RunInputs,
    stats_json: Option<&Path>,
) -> Vec<Clash> {
    let mut outputs = planned_outputs(world, inputs, stats_json);
    for out in &mut outputs {
        if let Origin::Scene(link, what) = &mut out.origin {
            if link.file.as_os_str().is_empty() && what.starts_with("options photon_map") {
                *link = super::locate::option_link(scene, "options.photon_map.file");
            }
        }
    }
    let mut refused = clashes(
        scene,
        &crate::scene::inputs::scene_inputs(scene, None),
        &outputs,
    );
    refused.extend(unwritable(&outputs));
    refused
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_resolve_dots_and_compare_equal() {
        assert_eq!(
            same_file_key(Path::new("a/./b/../c.png")),
            same_file_key(Path::new("a/c.png"))
        );
    }
}

//! Slurm batch scripts for a farm render or bake (`stagelight farm [--bake]`): a job array
//! whose task K runs `stagelight render SCENE --part K/N` (or `stagelight bake SCENE --part
//! K/N`), a merge job that waits for the whole array
//! (`--dependency=afterok:<array>`), and `submit.sh`, which submits both with `sbatch` and
//! prints their job ids. The scripts are plain, commented bash that a user can read, edit
//! and submit by hand. A bake of a glTF scene with `--write-gltf` gets the flag on its merge
//! command only (`merge --write-gltf` writes the baked glTF copy; parts cannot).
//!
//! Photon maps: when the render traces photon maps, a photon job runs first
//! (`stagelight photons SCENE --photon-cache OUT/photons`), the array waits for it
//! (`--dependency=afterok:<photon job>`) and every part loads the maps from that cache
//! instead of tracing them: one photon pass for the whole farm, and identical maps in every
//! part by construction.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use super::part::Split;
use super::sbatch_directive;

/// What to write scripts for.
#[derive(Debug, Clone)]
pub struct FarmJob {
    /// The stagelight executable the nodes run (absolute).
    pub exe: PathBuf,
    /// The scene (absolute).
    pub scene: PathBuf,
    /// Directory of the scripts, part files and logs (absolute).
    pub out: PathBuf,
    /// Working directory of the jobs (where the camera's relative output paths resolve).
    pub workdir: PathBuf,
    /// Number of parts.
    pub parts: u32,
    /// How the render is divided.
    pub split: Split,
    /// Bake the scene's bake requests instead of rendering its camera.
    pub bake: bool,
    /// A bake of a glTF scene whose merge also writes the baked glTF copy
    /// (`merge --write-gltf`).
    pub write_gltf: bool,
    /// Where the merge writes (`-o`); `None`: the camera's outputs (a bake: the working
    /// directory).
    pub output: Option<PathBuf>,
    /// Extra `render` arguments (`--spp N`, `--seed S`, `--integrator I`).
    pub render_args: Vec<String>,
    /// The render traces photon maps: a photon job fills `OUT/photons` before the array.
    pub photons: bool,
    /// Extra `photons` arguments (`--seed S`).
    pub photon_args: Vec<String>,
    /// `#SBATCH --partition`.
    pub partition: Option<String>,
    /// `#SBATCH --cpus-per-task` (each part uses that many threads).
    pub cpus_per_task: u32,
    /// `#SBATCH --mem` (e.g. `4G`).
    pub mem: Option<String>,
    /// `#SBATCH --time` (e.g. `01:00:00`).
    pub time: Option<String>,
}

/// One script file: its name in [`FarmJob::out`] and its text.
pub struct Script {
    /// File name.
    pub name: &'static str,
    /// Contents.
    pub text: String,
}

/// Quotes `s` for bash (single quotes; embedded quotes closed, escaped and reopened).
pub fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', r"'\''"))
}

fn q(p: &Path) -> String {
    quote(&p.to_string_lossy())
}

/// The part file of part `k` (as the merge job names it: `part_$K.exr`).
pub fn part_path(out: &Path, k: u32) -> PathBuf {
    out.join(format!("part_{k}.exr"))
}

/// The photon cache the photon job fills and the parts read.
pub fn photon_cache(out: &Path) -> PathBuf {
    out.join("photons")
}

/// The command of array task `$K` of `n`, without the executable.
fn part_command(job: &FarmJob, n: u32, extra: &str) -> String {
    let extra = if job.photons && !job.bake {
        format!("{extra} --photon-cache {}", q(&photon_cache(&job.out)))
    } else {
        extra.to_string()
    };
    if job.bake {
        // A bake part names its own file in the directory: `bake_part_K_of_N.exr`.
        format!(
            "bake {} --part \"$K/{n}\" --threads \"${{SLURM_CPUS_PER_TASK:-1}}\"{extra} -o {}",
            q(&job.scene),
            q(&job.out)
        )
    } else {
        format!(
            "render {} --part \"$K/{n}\" --split {} --threads \"${{SLURM_CPUS_PER_TASK:-1}}\"{extra} -o {}\"/part_$K.exr\"",
            q(&job.scene),
            job.split,
            q(&job.out)
        )
    }
}

/// A path in a comment line of a script: a line break in it would end the comment (and
/// the `#SBATCH` lines after it would be read as commands), so it is written `\n`.
fn comment_path(p: &Path) -> String {
    p.to_string_lossy()
        .replace('\n', "\\n")
        .replace('\r', "\\r")
}

/// The directives every job has: its name, its working directory and its log, the paths
/// written for sbatch's own parser ([`sbatch_directive`]).
fn common_directives(s: &mut String, job: &FarmJob, name: &str, log: &str) {
    let _ = writeln!(s, "#SBATCH --job-name={name}");
    let _ = writeln!(
        s,
        "#SBATCH --chdir={}",
        sbatch_directive::word(&job.workdir.to_string_lossy())
    );
    let _ = writeln!(
        s,
        "#SBATCH --output={}",
        sbatch_directive::word(&sbatch_directive::log_pattern(&job.out.join("logs"), log))
    );
    if let Some(p) = &job.partition {
        let _ = writeln!(s, "#SBATCH --partition={p}");
    }
    if let Some(t) = &job.time {
        let _ = writeln!(s, "#SBATCH --time={t}");
    }
}

/// The three scripts of `job`.
pub fn scripts(job: &FarmJob) -> Vec<Script> {
    let n = job.parts;
    let mut render = String::from("#!/bin/bash\n");
    let what = if job.bake {
        "bake, texel tiles".to_string()
    } else {
        format!("split: {}", job.split)
    };
    let _ = writeln!(
        render,
        "# stagelight farm: part $SLURM_ARRAY_TASK_ID of {n} of {} ({what}).",
        comment_path(&job.scene),
    );
    let _ = writeln!(
        render,
        "# A failed task is requeued by Slurm; re-run one by hand with\n#   sbatch --array=K {}",
        comment_path(&job.out.join("render.sbatch"))
    );
    common_directives(&mut render, job, "stagelight-render", "part_%a.log");
    let _ = writeln!(render, "#SBATCH --array=1-{n}");
    let _ = writeln!(render, "#SBATCH --cpus-per-task={}", job.cpus_per_task);
    let _ = writeln!(render, "#SBATCH --ntasks=1");
    if let Some(m) = &job.mem {
        let _ = writeln!(render, "#SBATCH --mem={m}");
    }
    render.push_str("#SBATCH --requeue\nset -euo pipefail\nK=\"$SLURM_ARRAY_TASK_ID\"\n");
    let extra: String = job
        .render_args
        .iter()
        .map(|a| format!(" {}", quote(a)))
        .collect();
    let _ = writeln!(
        render,
        "exec {} {}",
        q(&job.exe),
        part_command(job, n, &extra)
    );

    let mut merge = String::from("#!/bin/bash\n");
    let _ = writeln!(
        merge,
        "# stagelight farm: merges the {n} part files into the outputs of a local {}.",
        match (job.bake, job.write_gltf) {
            (true, true) => "bake --write-gltf (the textures and the baked glTF copy)",
            (true, false) => "bake",
            _ => "render",
        }
    );
    common_directives(&mut merge, job, "stagelight-merge", "merge.log");
    merge.push_str("#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\nset -euo pipefail\n");
    let part_file = if job.bake {
        format!("bake_part_${{k}}_of_{n}.exr")
    } else {
        "part_$k.exr".to_string()
    };
    let _ = writeln!(
        merge,
        "parts=()\nfor k in $(seq 1 {n}); do parts+=({}\"/{part_file}\"); done",
        q(&job.out)
    );
    let output = job
        .output
        .as_ref()
        .map(|o| format!(" -o {}", q(o)))
        .unwrap_or_default();
    let write_gltf = if job.write_gltf { " --write-gltf" } else { "" };
    let _ = writeln!(
        merge,
        "exec {} merge --scene {} \"${{parts[@]}}\" --threads \"${{SLURM_CPUS_PER_TASK:-1}}\"{output}{write_gltf}",
        q(&job.exe),
        q(&job.scene)
    );

    let mut photons = String::from("#!/bin/bash\n");
    let _ = writeln!(
        photons,
        "# stagelight farm: traces the photon maps of {} once into {}; every part loads them.",
        comment_path(&job.scene),
        comment_path(&photon_cache(&job.out))
    );
    common_directives(&mut photons, job, "stagelight-photons", "photons.log");
    let _ = writeln!(photons, "#SBATCH --ntasks=1");
    let _ = writeln!(photons, "#SBATCH --cpus-per-task={}", job.cpus_per_task);
    if let Some(m) = &job.mem {
        let _ = writeln!(photons, "#SBATCH --mem={m}");
    }
    photons.push_str("set -euo pipefail\n");
    let photon_extra: String = job
        .photon_args
        .iter()
        .map(|a| format!(" {}", quote(a)))
        .collect();
    let _ = writeln!(
        photons,
        "exec {} photons {} --photon-cache {} --threads \"${{SLURM_CPUS_PER_TASK:-1}}\"{photon_extra}",
        q(&job.exe),
        q(&job.scene),
        q(&photon_cache(&job.out))
    );

    let mut submit = String::from("#!/bin/bash\n");
    submit.push_str(if job.photons {
        "# Submits the photon job, the part array that waits for it, then the merge job that runs\n# once every part succeeded.\n"
    } else {
        "# Submits the part array, then the merge job that runs once every part succeeded.\n"
    });
    submit.push_str("set -euo pipefail\n");
    let _ = writeln!(submit, "mkdir -p {}", q(&job.out.join("logs")));
    let after_photons = if job.photons {
        let _ = writeln!(
            submit,
            "photons=$(sbatch --parsable {})\nphotons=\"${{photons%%;*}}\"\necho \"photon job $photons\"",
            q(&job.out.join("photons.sbatch"))
        );
        " --dependency=afterok:\"$photons\""
    } else {
        ""
    };
    let _ = writeln!(
        submit,
        "array=$(sbatch --parsable{after_photons} {})\narray=\"${{array%%;*}}\"",
        q(&job.out.join("render.sbatch"))
    );
    let _ = writeln!(
        submit,
        "merge=$(sbatch --parsable --dependency=afterok:\"$array\" {})\nmerge=\"${{merge%%;*}}\"",
        q(&job.out.join("merge.sbatch"))
    );
    submit.push_str("echo \"render array job $array\"\necho \"merge job $merge\"\n");
    let mut scripts = Vec::new();
    if job.photons {
        scripts.push(Script {
            name: "photons.sbatch",
            text: photons,
        });
    }
    scripts.extend([
        Script {
            name: "render.sbatch",
            text: render,
        },
        Script {
            name: "merge.sbatch",
            text: merge,
        },
        Script {
            name: "submit.sh",
            text: submit,
        },
    ]);
    scripts
}

/// The farm command's options besides the paths.
#[derive(Debug, Clone)]
pub struct JobOptions {
    /// Number of parts.
    pub parts: u32,
    /// How the render is divided.
    pub split: Split,
    /// Bake instead of render.
    pub bake: bool,
    /// With `bake`: the merge writes the baked glTF copy (`merge --write-gltf`).
    pub write_gltf: bool,
    /// The render traces photon maps (a photon job runs before the array).
    pub photons: bool,
    /// `--spp` for every part.
    pub spp: Option<u32>,
    /// `--seed` for every part.
    pub seed: Option<u64>,
    /// Slurm partition.
    pub partition: Option<String>,
    /// CPUs per part.
    pub cpus_per_task: u32,
    /// Memory per part.
    pub mem: Option<String>,
    /// Time limit.
    pub time: Option<String>,
}

/// A Slurm value (`--mem`, `--time`, `--partition`) must be one plain word: it goes on an
/// `#SBATCH` line unquoted.
fn plain(what: &str, value: &Option<String>) -> Result<(), String> {
    match value {
        Some(v)
            if v.is_empty()
                || !v
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "-_:.,".contains(c)) =>
        {
            Err(format!(
                "--{what} \"{v}\" is not a Slurm value (letters, digits and - _ : . , only)"
            ))
        }
        _ => Ok(()),
    }
}

/// Whether `sbatch` is an executable file in a directory of `PATH`, where `submit.sh` (run
/// by bash with this process's environment) looks for it.
pub fn sbatch_on_path() -> bool {
    let Some(paths) = std::env::var_os("PATH") else {
        return false;
    };
    std::env::split_paths(&paths).any(|dir| {
        let file = dir.join("sbatch");
        let Ok(meta) = std::fs::metadata(&file) else {
            return false;
        };
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            meta.is_file() && meta.permissions().mode() & 0o111 != 0
        }
        #[cfg(not(unix))]
        {
            meta.is_file()
        }
    })
}

/// Why the `#SBATCH` lines of a farm job with scripts in `out`, run from the working
/// directory, cannot be written ([`sbatch_directive::refusal`]); `None` when they can.
pub fn directive_refusal(out: &Path) -> Option<String> {
    let workdir = std::env::current_dir().ok()?;
    let out = if out.is_absolute() {
        out.to_path_buf()
    } else {
        workdir.join(out)
    };
    sbatch_directive::refusal(&out.join("logs"), &workdir)
}

/// The job for `scene` with scripts and parts in `out`, the executable being this one and
/// every path made absolute (the nodes may start elsewhere).
pub fn job(
    scene: &Path,
    out: &Path,
    output: Option<&Path>,
    options: JobOptions,
) -> Result<FarmJob, String> {
    plain("partition", &options.partition)?;
    plain("mem", &options.mem)?;
    plain("time", &options.time)?;
    let workdir =
        std::env::current_dir().map_err(|e| format!("cannot read the working directory: {e}"))?;
    let absolute = |p: &Path| {
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            workdir.join(p)
        }
    };
    let exe = std::env::current_exe()
        .map_err(|e| format!("cannot find the stagelight executable: {e}"))?;
    let mut render_args = Vec::new();
    if let Some(spp) = options.spp {
        render_args.extend(["--spp".to_string(), spp.to_string()]);
    }
    let mut photon_args = Vec::new();
    if let Some(seed) = options.seed {
        render_args.extend(["--seed".to_string(), seed.to_string()]);
        photon_args.extend(["--seed".to_string(), seed.to_string()]);
    }
    Ok(FarmJob {
        exe,
        scene: absolute(scene),
        out: absolute(out),
        workdir: workdir.clone(),
        parts: options.parts,
        split: options.split,
        bake: options.bake,
        write_gltf: options.bake && options.write_gltf,
        output: output.map(absolute),
        render_args,
        photons: options.photons && !options.bake,
        photon_args,
        partition: options.partition,
        cpus_per_task: options.cpus_per_task,
        mem: options.mem,
        time: options.time,
    })
}

/// Writes the scripts (executable) into `job.out` and creates its `logs/`; returns the
/// paths written.
pub fn write(job: &FarmJob) -> Result<Vec<PathBuf>, String> {
    let logs = job.out.join("logs");
    std::fs::create_dir_all(&logs).map_err(|e| format!("cannot create {}: {e}", logs.display()))?;
    let mut written = Vec::new();
    for script in scripts(job) {
        let path = job.out.join(script.name);
        std::fs::write(&path, &script.text)
            .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let _ = std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755));
        }
        written.push(path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn job() -> FarmJob {
        FarmJob {
            exe: "/opt/bin/stagelight".into(),
            scene: "/scenes/it's.ron".into(),
            out: "/farm/out".into(),
            workdir: "/scenes".into(),
            parts: 4,
            split: Split::Tiles,
            bake: false,
            write_gltf: false,
            output: Some("/farm/final.png".into()),
            render_args: vec!["--spp".into(), "16".into()],
            photons: false,
            photon_args: Vec::new(),
            partition: Some("render".into()),
            cpus_per_task: 8,
            mem: Some("4G".into()),
            time: None,
        }
    }

    #[test]
    fn the_array_renders_each_part_and_the_merge_waits_for_it() {
        let s = scripts(&job());
        let render = &s[0].text;
        assert!(render.contains("#SBATCH --array=1-4\n"), "{render}");
        assert!(render.contains("#SBATCH --partition=render\n"));
        assert!(render.contains("#SBATCH --cpus-per-task=8\n"));
        assert!(render.contains(
            "exec '/opt/bin/stagelight' render '/scenes/it'\\''s.ron' --part \"$K/4\" --split tiles --threads \"${SLURM_CPUS_PER_TASK:-1}\" '--spp' '16' -o '/farm/out'\"/part_$K.exr\"\n"
        ), "{render}");
        let merge = &s[1].text;
        assert!(
            merge.contains(
                "merge --scene '/scenes/it'\\''s.ron' \"${parts[@]}\" --threads \"${SLURM_CPUS_PER_TASK:-1}\" -o '/farm/final.png'"
            ),
            "{merge}"
        );
        let submit = &s[2].text;
        assert!(
            submit.contains("--dependency=afterok:\"$array\""),
            "{submit}"
        );
    }

    #[test]
    fn a_bake_array_bakes_each_part_and_the_merge_assembles_the_bake_parts() {
        let mut j = job();
        j.bake = true;
        j.render_args = vec!["--seed".into(), "3".into()];
        j.output = Some("/farm/textures".into());
        let s = scripts(&j);
        let render = &s[0].text;
        assert!(render.contains(
            "exec '/opt/bin/stagelight' bake '/scenes/it'\\''s.ron' --part \"$K/4\" --threads \"${SLURM_CPUS_PER_TASK:-1}\" '--seed' '3' -o '/farm/out'\n"
        ), "{render}");
        let merge = &s[1].text;
        assert!(
            merge.contains(
                "for k in $(seq 1 4); do parts+=('/farm/out'\"/bake_part_${k}_of_4.exr\"); done"
            ),
            "{merge}"
        );
        assert!(
            merge.contains(
                "\"${parts[@]}\" --threads \"${SLURM_CPUS_PER_TASK:-1}\" -o '/farm/textures'\n"
            ),
            "{merge}"
        );
    }

    #[test]
    fn a_gltf_bake_merge_writes_the_baked_gltf_copy() {
        let mut j = job();
        j.bake = true;
        j.write_gltf = true;
        j.scene = "/scenes/model.glb".into();
        j.output = None;
        let s = scripts(&j);
        let merge = &s[1].text;
        assert!(
            merge.contains(
                "exec '/opt/bin/stagelight' merge --scene '/scenes/model.glb' \"${parts[@]}\" --threads \"${SLURM_CPUS_PER_TASK:-1}\" --write-gltf\n"
            ),
            "{merge}"
        );
        assert!(
            merge.contains("local bake --write-gltf (the textures and the baked glTF copy)"),
            "{merge}"
        );
        assert!(
            !s[0].text.contains("--write-gltf"),
            "the parts bake without it"
        );
    }

    #[test]
    fn a_photon_job_runs_first_and_the_parts_load_its_maps() {
        let mut j = job();
        j.photons = true;
        j.photon_args = vec!["--seed".into(), "5".into()];
        let s = scripts(&j);
        let names: Vec<_> = s.iter().map(|s| s.name).collect();
        assert_eq!(
            names,
            [
                "photons.sbatch",
                "render.sbatch",
                "merge.sbatch",
                "submit.sh"
            ]
        );
        let photons = &s[0].text;
        assert!(photons.contains(
            "exec '/opt/bin/stagelight' photons '/scenes/it'\\''s.ron' --photon-cache '/farm/out/photons' --threads \"${SLURM_CPUS_PER_TASK:-1}\" '--seed' '5'\n"
        ), "{photons}");
        assert!(
            photons.contains("#SBATCH --cpus-per-task=8\n#SBATCH --mem=4G\n"),
            "{photons}"
        );
        let render = &s[1].text;
        assert!(
            render.contains("'--spp' '16' --photon-cache '/farm/out/photons' -o '/farm/out'"),
            "{render}"
        );
        let submit = &s[3].text;
        assert!(submit.contains(
            "photons=$(sbatch --parsable '/farm/out/photons.sbatch')\nphotons=\"${photons%%;*}\"\necho \"photon job $photons\"\narray=$(sbatch --parsable --dependency=afterok:\"$photons\" '/farm/out/render.sbatch')"
        ), "{submit}");
        assert!(
            submit.contains("--dependency=afterok:\"$array\""),
            "{submit}"
        );
    }
}

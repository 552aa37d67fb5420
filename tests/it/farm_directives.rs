//! The paths on `farm`'s `#SBATCH` lines, written for sbatch's own parser: it splits a
//! directive at whitespace, reads `'…'`/`"…"` quotes and backslash escapes, and takes an
//! unquoted `#` for a comment, so `--chdir=/proj/My Show` was two arguments and a `#` cut
//! the path short. `--output` is also a filename pattern (`%a` is the array index, `%%` a
//! `%`; a backslash switches the pattern off and is dropped), so a `%` of the directory is
//! doubled and a backslash in the log directory is refused.

use crate::common::cli::{dir_names, run_in, scratch_dir, stderr_of};

const SCENE: &str = r#"Scene(
    cameras: [(name: "cam", fov_y: 40.0, resolution: (32, 16),
               placement: LookAt(eye: (0, -4, 3), target: (0, 0, 0)),
               outputs: [(file: "out.png")])],
    lights: [(name: "sun", kind: Point(position: (0.5, 0, 3)), intensity: 2.0)],
    materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))],
    objects: [(name: "floor", mesh: Inline(
        vertices: [(-2, -2, 0), (2, -2, 0), (2, 2, 0), (-2, 2, 0)],
        polygons: [[0, 1, 2, 3]]), material: "grey")],
    instances: [(name: "floor_1", of: "floor")],
    groups: [(name: "world", members: ["floor_1"])],
    render: (root: "world", camera: "cam"),
)
"#;

#[test]
fn directive_paths_with_spaces_hashes_quotes_and_percents_are_quoted_for_sbatch() {
    let root = scratch_dir("farm-directives");
    let dir = root.join("My Show #1 \"100%\"");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("s.ron"), SCENE).unwrap();
    let o = run_in(&dir, &["farm", "s.ron", "--parts", "2", "--out", "job"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let work = std::fs::canonicalize(&dir).unwrap();
    let work = work.to_str().unwrap();
    let quoted = work.replace('"', "\\\"");
    let render = std::fs::read_to_string(dir.join("job/render.sbatch")).unwrap();
    let directives: Vec<&str> = render
        .lines()
        .filter(|l| l.starts_with("#SBATCH --chdir") || l.starts_with("#SBATCH --output"))
        .collect();
    let logs = quoted.replace('%', "%%");
    assert_eq!(
        directives,
        [
            format!("#SBATCH --chdir=\"{quoted}\""),
            format!("#SBATCH --output=\"{logs}/job/logs/part_%a.log\""),
        ],
        "{render}"
    );
    let merge = std::fs::read_to_string(dir.join("job/merge.sbatch")).unwrap();
    assert!(
        merge.contains(&format!("#SBATCH --output=\"{logs}/job/logs/merge.log\"\n")),
        "{merge}"
    );
    // A plain directory stays unquoted.
    let plain = root.join("plain");
    std::fs::create_dir_all(&plain).unwrap();
    std::fs::write(plain.join("s.ron"), SCENE).unwrap();
    let o = run_in(&plain, &["farm", "s.ron", "--parts", "2", "--out", "job"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let render = std::fs::read_to_string(plain.join("job/render.sbatch")).unwrap();
    let plain = std::fs::canonicalize(&plain).unwrap();
    assert!(
        render.contains(&format!("\n#SBATCH --chdir={}\n", plain.display())),
        "{render}"
    );
}

#[test]
fn a_log_directory_with_a_backslash_is_refused() {
    let dir = scratch_dir("farm-backslash");
    std::fs::write(dir.join("s.ron"), SCENE).unwrap();
    let o = run_in(&dir, &["farm", "s.ron", "--parts", "2", "--out", "a\\b"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    let logs = std::fs::canonicalize(&dir)
        .unwrap()
        .join("a\\b")
        .join("logs");
    assert_eq!(
        stderr_of(&o),
        format!(
            "error: the log directory \"{}\" has a backslash: Slurm drops every backslash of an `--output` path (and then replaces no %a), so the jobs' logs would go elsewhere\n  help: give --out a directory whose path has no line break or backslash\n",
            logs.display().to_string().replace('\\', "\\\\")
        )
    );
    assert_eq!(dir_names(&dir), ["s.ron"]);
}

//! Running the `stagelight` binary from tests: the command, a fresh scratch directory per
//! test, and the output as text.

use std::path::PathBuf;
use std::process::{Command, Output};

/// The `stagelight` binary under test.
pub fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_stagelight"))
}

/// A fresh, empty directory for `test` (unique per process).
pub fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stagelight-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs `cmd` to completion.
pub fn run(cmd: &mut Command) -> Output {
    cmd.output().expect("run stagelight")
}

/// Its standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

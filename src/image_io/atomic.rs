//! Whole-or-nothing file output: write every file under a temporary name, then rename them
//! all into place.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};

/// An encoded file waiting to be written.
#[derive(Debug, Clone)]
pub struct PendingFile {
    /// Final destination.
    pub path: PathBuf,
    /// Encoded bytes.
    pub bytes: Vec<u8>,
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes every file to a temporary sibling, then renames all into place. On any failure the
/// temporaries are removed and no destination is touched (renames are the last step).
pub fn commit_all(files: &[PendingFile]) -> Result<Vec<PathBuf>, (PathBuf, std::io::Error)> {
    let mut temps = Vec::with_capacity(files.len());
    for f in files {
        let tmp = temp_path(&f.path);
        let result = (|| {
            if let Some(dir) = f.path.parent().filter(|d| !d.as_os_str().is_empty()) {
                fs::create_dir_all(dir)?;
            }
            let mut file = fs::File::create(&tmp)?;
            file.write_all(&f.bytes)?;
            file.sync_all()
        })();
        if let Err(e) = result {
            let _ = fs::remove_file(&tmp);
            for t in &temps {
                let _ = fs::remove_file(t);
            }
            return Err((f.path.clone(), e));
        }
        temps.push(tmp);
    }
    let mut written = Vec::with_capacity(files.len());
    for (f, tmp) in files.iter().zip(&temps) {
        if let Err(e) = fs::rename(tmp, &f.path) {
            for t in &temps {
                let _ = fs::remove_file(t);
            }
            return Err((f.path.clone(), e));
        }
        written.push(f.path.clone());
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_files_and_leaves_no_temporaries() {
        let dir = std::env::temp_dir().join(format!("stagelight-atomic-{}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        let files = vec![
            PendingFile {
                path: dir.join("a.bin"),
                bytes: vec![1, 2, 3],
            },
            PendingFile {
                path: dir.join("sub/b.bin"),
                bytes: vec![4],
            },
        ];
        commit_all(&files).unwrap();
        assert_eq!(fs::read(dir.join("a.bin")).unwrap(), vec![1, 2, 3]);
        assert_eq!(fs::read(dir.join("sub/b.bin")).unwrap(), vec![4]);
        let leftovers: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
            .collect();
        assert!(leftovers.is_empty());
        fs::remove_dir_all(&dir).unwrap();
    }
}

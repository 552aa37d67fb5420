//! The help of a file a scene names but that is not there (an include, a mesh file): a path
//! is read relative to the file that names it, so the help says which file that is and,
//! when the directory it points into holds a file of a similar name, suggests that one.

use std::path::Path;

use super::suggest::closest;

/// The help for `written` when the file it resolves to, `tried`, does not exist (`None`
/// when it does: it was unreadable for another reason, which the message says).
pub fn help_if_missing(written: &str, tried: &Path, naming: &Path) -> Option<String> {
    match std::fs::metadata(tried) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Some(help(written, tried, naming)),
        _ => None,
    }
}

/// The help for `written` (the path as the scene file `naming` writes it), resolved to
/// `tried`, which does not exist: `"meshes/cube2.obj" is read relative to scenes/a.ron, the
/// file that names it; did you mean "meshes/cube.obj"?`.
fn help(written: &str, tried: &Path, naming: &Path) -> String {
    let relative = format!(
        "\"{written}\" is read relative to {}, the file that names it",
        naming.display()
    );
    let dir = tried.parent().filter(|d| !d.as_os_str().is_empty());
    let listing = std::fs::read_dir(dir.unwrap_or(Path::new(".")));
    let Ok(entries) = listing else {
        return match dir {
            Some(d) => format!("{relative}; there is no directory {}", d.display()),
            None => relative,
        };
    };
    let mut names: Vec<String> = entries
        .filter_map(Result::ok)
        .filter(|e| e.file_type().is_ok_and(|t| t.is_file()))
        .filter_map(|e| e.file_name().into_string().ok())
        .collect();
    // Directory order is the file system's: sorted, a tie picks the same name every run.
    names.sort();
    let wanted = tried
        .file_name()
        .and_then(|n| n.to_str())
        .unwrap_or_default();
    match closest(wanted, names.iter().map(String::as_str)) {
        Some(similar) => {
            let suggested = Path::new(written).with_file_name(similar);
            format!("{relative}; did you mean \"{}\"?", suggested.display())
        }
        None => relative,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_similar_name_in_the_directory_is_suggested() {
        let dir = std::env::temp_dir().join(format!("sl-missing-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("meshes")).unwrap();
        std::fs::write(dir.join("meshes/cube.obj"), "").unwrap();
        std::fs::write(dir.join("meshes/zzz.obj"), "").unwrap();
        let scene = dir.join("a.ron");
        let got = help("meshes/cube2.obj", &dir.join("meshes/cube2.obj"), &scene);
        assert_eq!(
            got,
            format!(
                "\"meshes/cube2.obj\" is read relative to {}, the file that names it; did you mean \"meshes/cube.obj\"?",
                scene.display()
            )
        );
        let got = help("meshes/sphere.obj", &dir.join("meshes/sphere.obj"), &scene);
        assert_eq!(
            got,
            format!(
                "\"meshes/sphere.obj\" is read relative to {}, the file that names it",
                scene.display()
            )
        );
        let got = help("lib/x.ron", &dir.join("lib/x.ron"), &scene);
        assert_eq!(
            got,
            format!(
                "\"lib/x.ron\" is read relative to {}, the file that names it; there is no directory {}",
                scene.display(),
                dir.join("lib").display()
            )
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

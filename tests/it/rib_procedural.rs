//! RIB `Procedural`: `DelayedReadArchive` reads its file as `ReadArchive` does, where it
//! stands (the same description, inside object definitions too), with the same located
//! errors for a missing file and for nesting; its arguments are checked; `RunProgram`,
//! `DynamicLoad`, unknown procedures and `Procedural2` are located warnings that their
//! geometry is missing.

use std::path::Path;

use stagelight::scene::import::rib::read_rib;
use stagelight::scene::import::to_ron::to_ron;

use crate::common::cli::scratch_dir;
use crate::common::read_rib_at;

const HEAD: &str = "Format 16 16 1\nTranslate 0 0 8\nWorldBegin\n";

/// Every message of reading `text` as `dir/main.rib` (errors and warnings, in order).
fn messages(dir: &Path, text: &str) -> Vec<String> {
    let path = dir.join("main.rib");
    let out = match read_rib(&path, text.as_bytes()) {
        Ok(s) => s.warnings,
        Err(e) => e,
    };
    let prefix = format!("{}/", dir.display());
    out.iter()
        .map(|m| m.to_string().replace(&prefix, ""))
        .collect()
}

/// The RON of the description read from `text` as `dir/main.rib`, which must have no
/// warnings.
fn ron(dir: &Path, text: &str) -> String {
    let s = read_rib_at(&dir.join("main.rib"), text);
    let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
    assert!(w.is_empty(), "{w:?}");
    to_ron(&s.desc).unwrap()
}

#[test]
fn delayed_read_archive_is_read_as_read_archive_where_it_stands() {
    let dir = scratch_dir("rib-delayed-archive");
    std::fs::write(
        dir.join("ball.rib"),
        "Color [1 0 0]\nSurface \"matte\"\nSphere 1 -1 1 360\n",
    )
    .unwrap();
    let scene = |call: &str| {
        format!(
            "{HEAD}LightSource \"pointlight\" 1 \"intensity\" [40] \"from\" [0 4 -4]\n\
             AttributeBegin\nTranslate 2 0 0\n{call}\nAttributeEnd\n\
             Polygon \"P\" [-4 -1 -4  4 -1 -4  4 -1 4  -4 -1 4]\nWorldEnd\n"
        )
    };
    let delayed = ron(
        &dir,
        &scene("Procedural \"DelayedReadArchive\" [\"ball.rib\"] [-1 1 -1 1 -1 1]"),
    );
    let read = ron(&dir, &scene("ReadArchive \"ball.rib\""));
    assert_eq!(delayed, read);
    let s = read_rib(
        &dir.join("main.rib"),
        scene("Procedural \"DelayedReadArchive\" [\"ball.rib\"] [-1 1 -1 1 -1 1]").as_bytes(),
    )
    .unwrap();
    // The sphere and the polygon; the sphere's file is one of the scene's inputs.
    assert_eq!(s.desc.objects.len(), 2);
    assert_eq!(s.read_files, [dir.join("ball.rib")]);
    // The bound is only a culling hint: a bound that misses the sphere reads the same.
    let elsewhere = ron(
        &dir,
        &scene("Procedural \"DelayedReadArchive\" [\"ball.rib\"] [50 51 50 51 50 51]"),
    );
    assert_eq!(elsewhere, read);
    // Inside an object definition it adds to the object, placed by each instance.
    std::fs::write(dir.join("shape.rib"), "Sphere 1 -1 1 360\n").unwrap();
    let defined = ron(
        &dir,
        &format!(
            "{HEAD}ObjectBegin \"o\"\nProcedural \"DelayedReadArchive\" [\"shape.rib\"] \
             [-1 1 -1 1 -1 1]\nObjectEnd\nObjectInstance \"o\"\nTranslate 3 0 0\n\
             ObjectInstance \"o\"\nWorldEnd\n"
        ),
    );
    let read_defined = ron(
        &dir,
        &format!(
            "{HEAD}ObjectBegin \"o\"\nReadArchive \"shape.rib\"\nObjectEnd\nObjectInstance \"o\"\n\
             Translate 3 0 0\nObjectInstance \"o\"\nWorldEnd\n"
        ),
    );
    assert_eq!(defined, read_defined);
    assert_eq!(defined.matches("of: \"sphere_1\"").count(), 2, "{defined}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn delayed_read_archive_reports_a_missing_file_and_deep_nesting_at_its_file_name() {
    let dir = scratch_dir("rib-delayed-archive-errors");
    assert_eq!(
        messages(
            &dir,
            &format!(
                "{HEAD}Procedural \"DelayedReadArchive\" [ \"gone.rib\" ] [-1 1 -1 1 -1 1]\nWorldEnd\n"
            )
        ),
        ["main.rib:4:35: error: cannot read archive \"gone.rib\": file not found"]
    );
    std::fs::write(
        dir.join("self.rib"),
        "Procedural \"DelayedReadArchive\" [\"self.rib\"] [-1 1 -1 1 -1 1]\n",
    )
    .unwrap();
    assert_eq!(
        messages(&dir, &format!("{HEAD}ReadArchive \"self.rib\"\nWorldEnd\n")),
        ["self.rib:1:34: error: DelayedReadArchive nests deeper than 16 files"]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn delayed_read_archive_arguments_are_checked_where_they_are() {
    let dir = scratch_dir("rib-delayed-archive-forms");
    // The file the well-formed calls read (empty).
    std::fs::write(dir.join("a.rib"), "").unwrap();
    let help = "\n  help: write it as Procedural \"DelayedReadArchive\" [\"file.rib\"] [xmin xmax ymin ymax zmin zmax]";
    let cases = [
        (
            "Procedural \"DelayedReadArchive\" [\"a.rib\" \"b.rib\"] [-1 1 -1 1 -1 1]",
            format!("main.rib:4:33: error: Procedural \"DelayedReadArchive\" takes 1 file name, found 2{help}"),
        ),
        (
            "Procedural \"DelayedReadArchive\" [] [-1 1 -1 1 -1 1]",
            format!("main.rib:4:33: error: Procedural \"DelayedReadArchive\" takes 1 file name, found 0{help}"),
        ),
        (
            "Procedural \"DelayedReadArchive\" [1 2] [-1 1 -1 1 -1 1]",
            format!("main.rib:4:33: error: expected an array of strings for the file name of Procedural \"DelayedReadArchive\", found an array of numbers{help}"),
        ),
        (
            "Procedural \"DelayedReadArchive\" [\"a.rib\"]",
            format!("main.rib:4:1: error: Procedural \"DelayedReadArchive\" needs a bound (6 numbers: xmin xmax ymin ymax zmin zmax){help}"),
        ),
        (
            "Procedural \"DelayedReadArchive\" [\"a.rib\"] [-1 1 -1 1]",
            "main.rib:4:43: error: the bound of Procedural \"DelayedReadArchive\" takes 6 numbers (xmin xmax ymin ymax zmin zmax), found 4".to_string(),
        ),
        (
            "Procedural \"DelayedReadArchive\" [\"a.rib\"] [\"x\"]",
            format!("main.rib:4:43: error: expected 6 numbers for the bound of Procedural \"DelayedReadArchive\", found an array of strings{help}"),
        ),
        (
            "Procedural \"DelayedReadArchive\" [\"a.rib\"] [-1 1 -1 1 -1 1] 7",
            "main.rib:4:60: error: too many arguments for Procedural".to_string(),
        ),
    ];
    for (call, expected) in cases {
        assert_eq!(
            messages(&dir, &format!("{HEAD}{call}\nWorldEnd\n")),
            [expected],
            "{call}"
        );
    }
    assert_eq!(
        messages(
            &dir,
            "Procedural \"DelayedReadArchive\" [\"a.rib\"] [-1 1 -1 1 -1 1]\nWorldBegin\nWorldEnd\n"
        ),
        ["main.rib:1:1: error: Procedural \"DelayedReadArchive\" before WorldBegin\n  help: geometry and lights go between WorldBegin and WorldEnd"]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn other_procedurals_are_warnings_that_their_geometry_is_missing() {
    let dir = scratch_dir("rib-procedural-missing");
    let text = format!(
        "{HEAD}Procedural \"RunProgram\" [\"gen\" \"1 2\"] [-1 1 -1 1 -1 1]\n\
         Procedural \"DynamicLoad\" [\"grass.so\" \"\"] [-1 1 -1 1 -1 1]\n\
         Procedural \"DelayedReadArchiv\" [\"a.rib\"] [-1 1 -1 1 -1 1]\n\
         Procedural2 \"DelayedReadArchive2\" \"SimpleBound\" \"string filename\" [\"a.rib\"] \"float[6] bound\" [-1 1 -1 1 -1 1]\n\
         ObjectBegin 1\nProcedural \"RunProgram\" [\"gen\" \"\"] [-1 1 -1 1 -1 1]\nObjectEnd\n\
         WorldEnd\n"
    );
    assert_eq!(
        messages(&dir, &text),
        [
            "main.rib:4:12: warning: ignored Procedural \"RunProgram\": stagelight runs no programs: the geometry it would make is missing\n  help: run the program yourself, save the RIB it writes and read that with ReadArchive",
            "main.rib:5:12: warning: ignored Procedural \"DynamicLoad\": stagelight loads no plug-ins: the geometry it would make is missing\n  help: have the plug-in's renderer write the geometry as RIB and read that with ReadArchive",
            "main.rib:6:12: warning: ignored Procedural \"DelayedReadArchiv\": not one of RenderMan's procedurals: the geometry it would make is missing\n  help: did you mean \"DelayedReadArchive\"?",
            "main.rib:7:13: warning: ignored Procedural2 \"DelayedReadArchive2\": stagelight loads no plug-ins: the geometry it would make is missing\n  help: for Procedural2 \"DelayedReadArchive2\", read its file with ReadArchive \"file.rib\" (or Procedural \"DelayedReadArchive\")",
            "main.rib:9:12: warning: ignored Procedural \"RunProgram\": stagelight runs no programs: the geometry it would make is missing\n  help: run the program yourself, save the RIB it writes and read that with ReadArchive",
        ]
    );
    let _ = std::fs::remove_dir_all(&dir);
}

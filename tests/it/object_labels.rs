//! Object labels: a `.mi` object's `tag N` is what its `tag` output (the `ObjectId` pass,
//! `id.object`) holds wherever the object is seen, as mental ray's tag buffer holds object
//! labels; an object without one keeps 1 + its instance's index, the background 0.
//! `convert` writes the labels as RON `label:`, so the RON renders the same tag bytes.

use std::path::Path;

use stagelight::scene::import::mi::read_mi;
use stagelight::scene::{load_scene, load_scene_str};

use crate::common::cli::{run_in, scratch, stderr_of};
use crate::common::{mi_preamble, small_scene, BASE};

/// Three quads at z = −2 seen by the shared 16 × 12 camera (the image plane spans ±4/3 by ±1
/// at distance 1, so ±8/3 by ±2 at the quads): `Left` (x ∈ [−2.4, −1], `tag left`),
/// `Middle` (|x| < 0.6, no tag), `Right` (x ∈ [1, 2.4], `tag label 7`), each |y| < 1; a `tag`
/// output beside the colour one.
fn mi_scene(left: &str) -> String {
    let preamble = mi_preamble(BASE, "output \"tag\" \"exr\" \"tag.exr\"\n")
        .replace("resolution 160 120", "resolution 16 12");
    let quad = |name: &str, tag: &str, x0: f64, x1: f64| {
        format!(
            "object \"{name}\"\nvisible trace shadow\n{tag}group\n{x0} -1 -2\n{x1} -1 -2\n{x1} 1 -2\n{x0} 1 -2\nv 0\nv 1\nv 2\nv 3\np \"grey\" 0 1 2 3\nend group\nend object\ninstance \"{name}_inst\" \"{name}\"\nend instance\n"
        )
    };
    format!(
        "{preamble}material \"grey\"\n\"mib_illum_lambert\" (\"ambient\" 0.5 0.5 0.5, \"ambience\" 1 1 1)\nend material\n{}{}{}instgroup \"rootgrp\"\n\"Camera_inst\" \"Left_inst\" \"Middle_inst\" \"Right_inst\"\nend instgroup\nrender \"rootgrp\" \"Camera_inst\" \"opt\"\n",
        quad("Left", &format!("tag {left}\n"), -2.4, -1.0),
        quad("Middle", "", -0.6, 0.6),
        quad("Right", "tag label 7\n", 1.0, 2.4),
    )
}

/// The `id.object` a pixel centre of the 16 × 12 image sees.
fn expected_id(i: usize, j: usize) -> u32 {
    let x = 2.0 * ((i as f64 + 0.5) / 16.0 * 2.0 - 1.0) * 4.0 / 3.0;
    let y = 2.0 * (1.0 - (j as f64 + 0.5) / 12.0 * 2.0);
    if y.abs() >= 1.0 {
        0
    } else if (-2.4..-1.0).contains(&x) {
        3
    } else if x.abs() < 0.6 {
        // Untagged: 1 + the index of its instance (Left 0, Middle 1, Right 2).
        2
    } else if (1.0..2.4).contains(&x) {
        7
    } else {
        0
    }
}

fn exr_object_ids(path: &Path) -> Vec<u32> {
    let read = exr::prelude::read_all_flat_layers_from_file(path).unwrap();
    let ids = read.layer_data[0]
        .channel_data
        .list
        .iter()
        .find(|c| c.name.to_string() == "id.object")
        .expect("id.object channel");
    match &ids.sample_data {
        exr::prelude::FlatSamples::U32(v) => v.clone(),
        other => panic!("id.object is not u32: {other:?}"),
    }
}

#[test]
fn mi_object_tags_are_the_tag_pass_values_and_convert_keeps_them() {
    let dir = scratch("object-labels");
    std::fs::write(dir.join("tags.mi"), mi_scene("3")).unwrap();
    let mut scene = load_scene(&dir.join("tags.mi")).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    let image = crate::common::render(&mut scene.world, settings)
        .outputs
        .image
        .expect("an image");
    let expected: Vec<u32> = (0..12)
        .flat_map(|j| (0..16).map(move |i| expected_id(i, j)))
        .collect();
    assert_eq!(image.object_id, expected);
    for id in [0, 2, 3, 7] {
        assert!(expected.contains(&id), "the image shows {id}");
    }

    let run = |args: &[&str]| {
        let o = run_in(&dir, args);
        assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
    };
    run(&["convert", "tags.mi", "-o", "tags.ron"]);
    let ron = std::fs::read_to_string(dir.join("tags.ron")).unwrap();
    assert_eq!(ron.matches("label: 3,").count(), 1, "{ron}");
    assert_eq!(ron.matches("label: 7,").count(), 1, "{ron}");
    assert_eq!(
        ron.matches("label:").count(),
        2,
        "the untagged object has none: {ron}"
    );
    run(&["render", "tags.mi"]);
    let from_mi = std::fs::read(dir.join("tag.exr")).unwrap();
    assert_eq!(exr_object_ids(&dir.join("tag.exr")), expected);
    std::fs::remove_file(dir.join("tag.exr")).unwrap();
    run(&["render", "tags.ron"]);
    assert_eq!(
        from_mi,
        std::fs::read(dir.join("tag.exr")).unwrap(),
        "the converted RON writes the same tag bytes"
    );
}

#[test]
fn a_tag_that_is_not_a_whole_number_is_a_located_error() {
    let text = mi_scene("-1");
    let line = text.lines().position(|l| l == "tag -1").unwrap() + 1;
    let e = read_mi(Path::new("t.mi"), text.as_bytes()).err().unwrap();
    let messages: Vec<String> = e.iter().map(|p| p.to_string()).collect();
    assert!(
        messages.iter().any(|m| m.starts_with(&format!(
            "t.mi:{line}:5: error: tag must be a whole number ≥ 0, found -1"
        ))),
        "{messages:?}"
    );
}

#[test]
fn ron_labels_reach_the_object_id_pass_and_a_scatter_cannot_have_one() {
    let text = small_scene(
        &crate::common::quad_object("quad")
            .replace("material: \"grey\")", "material: \"grey\", label: 41)"),
        "(name: \"quad_1\", of: \"quad\")",
        "(file: \"ids.exr\", passes: [ObjectId])",
        "",
    );
    let mut scene = load_scene_str(&text, Path::new("l.ron")).unwrap_or_else(|e| panic!("{e}"));
    let settings = scene.settings.clone();
    let ids = crate::common::render(&mut scene.world, settings)
        .outputs
        .image
        .expect("an image")
        .object_id;
    // The camera at z = 3 (fov 40°) sees the unit quad in the middle.
    assert_eq!(ids[4 * 8 + 4], 41);
    assert!(ids.iter().all(|&id| id == 0 || id == 41), "{ids:?}");

    let text = small_scene(
        &format!(
            "{}\n        (name: \"balls\", mesh: Scatter(prototype: \"quad\", surface: \"quad\", count: 4, seed: 3), label: 5),",
            crate::common::quad_object("quad")
        ),
        "(name: \"b\", of: \"balls\")",
        "(file: \"ids.exr\", passes: [ObjectId])",
        "",
    );
    let e = load_scene_str(&text, Path::new("s.ron"))
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("error: a scatter has no surface of its own: label the prototype"),
        "{e}"
    );
}

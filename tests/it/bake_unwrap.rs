//! Bakes on generated lightmap UVs (`uvs: Unwrap`) sized from texel density: the charts are
//! packed for the final texture, so `padding` holds in its texels and the size follows the
//! requested density; and the help when generated charts do not fit the texture.

use std::path::Path;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

/// A 2 × 2 × 2 box and a 2 × 2 quad, each with the bake settings given.
fn scene(box_bake: &str, quad_bake: &str) -> String {
    format!(
        r#"Scene(
    cameras: [(name: "cam", fov_y: 40, resolution: (4, 4),
               placement: LookAt(eye: (0, 0, 9), target: (0, 0, 0), up: (0, 1, 0)))],
    materials: [(name: "w", shader: Lambert(albedo: (0.8, 0.8, 0.8)))],
    objects: [
        (name: "box", mesh: Inline(
            vertices: [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                       (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],
            polygons: [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [2, 3, 7, 6], [1, 2, 6, 5],
                       [0, 4, 7, 3]]), material: "w"),
        (name: "quad", mesh: Inline(
            vertices: [(-1, -1, 3), (1, -1, 3), (1, 1, 3), (-1, 1, 3)],
            polygons: [[0, 1, 2, 3]]), material: "w"),
    ],
    instances: [(name: "b", of: "box", bake: ({box_bake}uvs: Unwrap, mask: true,
                     outputs: [(kind: AmbientOcclusion(samples: 4))])),
                (name: "q", of: "quad", bake: ({quad_bake}uvs: Unwrap, mask: true,
                     outputs: [(kind: AmbientOcclusion(samples: 4))]))],
    groups: [(name: "world", members: ["b", "q"])],
    render: (root: "world", camera: "cam"),
)
"#
    )
}

/// The mask's covered texels, one flag per texel (rows top to bottom), and its size.
fn mask(path: &Path) -> (Vec<bool>, u32, u32) {
    let img = crate::common::png::read(path);
    let n = (img.width * img.height) as usize;
    let covered = (0..n).map(|p| img.rgba(p)[0] > 0.5).collect();
    (covered, img.width, img.height)
}

/// The 8-connected components of the covered texels: each texel's component, or `None`.
fn components(covered: &[bool], width: u32, height: u32) -> (Vec<Option<usize>>, usize) {
    let (w, h) = (width as i64, height as i64);
    let mut label = vec![None; covered.len()];
    let mut count = 0;
    for start in 0..covered.len() {
        if !covered[start] || label[start].is_some() {
            continue;
        }
        label[start] = Some(count);
        let mut stack = vec![start];
        while let Some(p) = stack.pop() {
            let (x, y) = (p as i64 % w, p as i64 / w);
            for (dx, dy) in (-1..=1).flat_map(|dx| (-1..=1).map(move |dy| (dx, dy))) {
                let (nx, ny) = (x + dx, y + dy);
                let q = (ny * w + nx) as usize;
                if (0..w).contains(&nx) && (0..h).contains(&ny) && covered[q] && label[q].is_none()
                {
                    label[q] = Some(count);
                    stack.push(q);
                }
            }
        }
        count += 1;
    }
    (label, count)
}

/// `texels_per_unit: 8` on the unwrapped box: 64² texels, six charts (the faces) with at
/// least `2 × padding` empty texels between any two (no texel takes samples of two faces);
/// the faces were packed on a 1024² page and scaled down, so ⅛ texel of padding was left and
/// the six faces covered one solid block. The 2 × 2 quad at 32 texels/unit is 64² (its
/// chart 60 texels wide inside the padding), not 128²: the padding of the 1024² page had
/// pushed the size past 64.
#[test]
fn density_sized_unwrapped_charts_keep_their_padding_and_the_requested_size() {
    let dir = scratch_dir("bake-unwrap-density");
    let padding = 2;
    std::fs::write(
        dir.join("scene.ron"),
        scene(
            &format!("texels_per_unit: 8, padding: {padding}, "),
            "texels_per_unit: 32, ",
        ),
    )
    .unwrap();
    let o = run_in(&dir, &["bake", "scene.ron", "-o", "out", "--stats"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
    let (covered, width, height) = mask(&dir.join("out/b_mask.png"));
    assert_eq!((width, height), (64, 64));
    let (label, charts) = components(&covered, width, height);
    assert_eq!(charts, 6, "the box's six faces as separate charts");
    let texels: Vec<(i64, i64, usize)> = label
        .iter()
        .enumerate()
        .filter_map(|(p, l)| l.map(|l| ((p as u32 % width) as i64, (p as u32 / width) as i64, l)))
        .collect();
    let mut nearest = i64::MAX;
    for &(x, y, l) in &texels {
        for &(u, v, m) in &texels {
            if l != m {
                nearest = nearest.min((x - u).abs().max((y - v).abs()));
            }
        }
    }
    assert!(
        nearest > 2 * padding,
        "charts {} texels apart: fewer than {} empty texels between them",
        nearest,
        2 * padding
    );
    let (quad, width, height) = mask(&dir.join("out/q_mask.png"));
    assert_eq!((width, height), (64, 64));
    assert_eq!(quad.iter().filter(|&&c| c).count(), 60 * 60);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Generated charts that do not fit the texture (the unwrapper spreads them over several
/// pages, which overlap, or they fall between the sample positions) are refused with help
/// to give the texture more texels or the charts less padding — not to set `uvs: Unwrap`,
/// which the request already has.
#[test]
fn generated_charts_that_do_not_fit_say_to_raise_the_size_or_lower_the_padding() {
    let dir = scratch_dir("bake-unwrap-fit");
    let cases = [
        (
            "resolution: (32, 32), padding: 8, ",
            "its UVs overlap (169 of 169 sample positions lie in two or more triangles); ao needs unique UVs\n  help: the generated lightmap UVs do not fit a 32×32 texture with `padding: 8`: raise `resolution`, or lower `padding`",
        ),
        (
            "resolution: (1, 1), ",
            "its UVs cover no texel of the texture (they lie outside [0, 1]², or between the sample positions)\n  help: the generated lightmap UVs do not fit a 1×1 texture with `padding: 2`: raise `resolution`, or lower `padding`",
        ),
        (
            "texels_per_unit: 8, max_size: 16, padding: 8, ",
            "its UVs overlap (100 of 100 sample positions lie in two or more triangles); ao needs unique UVs\n  help: the generated lightmap UVs do not fit a 16×16 texture with `padding: 8`: raise `max_size`, or lower `padding`",
        ),
    ];
    for (bake, message) in cases {
        std::fs::write(dir.join("scene.ron"), scene(bake, "texels_per_unit: 32, ")).unwrap();
        let o = run_in(&dir, &["bake", "scene.ron", "-o", "out"]);
        assert_eq!(o.status.code(), Some(1), "{bake}");
        assert_eq!(
            stderr_of(&o),
            format!("scene.ron:15:17: error: bake request on instance \"b\": {message}\n"),
            "{bake}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

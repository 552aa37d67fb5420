//! An inside-out RIB primitive (`ReverseOrientation`) with normals of its own (`"N"`, kept
//! as written, so pointing out of the side that is now the back): it renders exactly as
//! without them, only its geometric normal deciding the front, and `bake --write-gltf`
//! writes its `NORMAL` out of the written triangles' counter-clockwise front, not the
//! written `N` (which pointed behind it).

use std::path::Path;

use glam::Vec3;

use crate::common::cli::{run_in, scratch_dir, stderr_of};

fn ok(dir: &Path, args: &[&str]) {
    let o = run_in(dir, args);
    assert!(o.status.success(), "{args:?}: {}", stderr_of(&o));
}

/// A one-sided quad (`Sides 1`) whose vertices run counter-clockwise as the camera sees
/// them, so its RIB outside faces away from the camera, turned inside out by
/// `ReverseOrientation`: its front faces the camera and the light beside it. `normals` is
/// written after the points (`"N"` along the outside, +z, or nothing).
fn scene(normals: &str) -> String {
    format!(
        "Display \"out.png\" \"file\" \"rgb\"\nFormat 16 12 1\nProjection \"perspective\" \"fov\" 40\n\
         Translate 0 0 5\nWorldBegin\nLightSource \"pointlight\" 1 \"from\" [0 0 -3] \"intensity\" 4\n\
         AttributeBegin\nAttribute \"identifier\" \"name\" [\"quad\"]\nSides 1\nReverseOrientation\n\
         Polygon \"P\" [-1 -1 0  1 -1 0  1 1 0  -1 1 0]{normals}\nAttributeEnd\nWorldEnd\n"
    )
}

const OUTSIDE_N: &str = " \"N\" [0 0 1  0 0 1  0 0 1  0 0 1]";

#[test]
fn an_inside_out_quad_with_normals_renders_as_without_them() {
    let dir = scratch_dir("rib-reversed-normals-render");
    std::fs::write(dir.join("n.rib"), scene(OUTSIDE_N)).unwrap();
    std::fs::write(dir.join("g.rib"), scene("")).unwrap();
    ok(&dir, &["render", "n.rib", "-o", "n.png"]);
    ok(&dir, &["render", "g.rib", "-o", "g.png"]);
    let (n, g) = (
        crate::common::png::read(&dir.join("n.png")),
        crate::common::png::read(&dir.join("g.png")),
    );
    // The front faces the camera and the light: the quad is seen and lit.
    let centre = crate::common::png::rgb8(&g, 8, 6);
    assert!(centre.iter().all(|&c| c > 0), "{centre:?}");
    assert_eq!(
        std::fs::read(dir.join("n.png")).unwrap(),
        std::fs::read(dir.join("g.png")).unwrap(),
        "the written normals point out of the back: shading turns them to the front"
    );
    assert_eq!(crate::common::png::rgb8(&n, 8, 6), centre);
    let _ = std::fs::remove_dir_all(&dir);
}

/// Each triangle of the first node of the `.glb` at `path`: its corners and their `NORMAL`.
fn triangles_with_normals(path: &Path) -> Vec<([Vec3; 3], [Vec3; 3])> {
    let bytes = std::fs::read(path).unwrap();
    let glb = gltf::Gltf::from_slice(&bytes).expect("a valid glb");
    let blob = glb.blob.clone().expect("a BIN chunk");
    let node = glb.nodes().next().unwrap();
    let prim = node.mesh().unwrap().primitives().next().unwrap();
    let reader = prim.reader(|_| Some(&blob));
    let p: Vec<Vec3> = reader.read_positions().unwrap().map(Vec3::from).collect();
    let n: Vec<Vec3> = reader.read_normals().unwrap().map(Vec3::from).collect();
    let indices: Vec<u32> = reader.read_indices().unwrap().into_u32().collect();
    indices
        .chunks(3)
        .map(|t| {
            (
                [0, 1, 2].map(|k| p[t[k] as usize]),
                [0, 1, 2].map(|k| n[t[k] as usize]),
            )
        })
        .collect()
}

/// The inside-out quad with its outside `"N"`, converted to RON (which keeps
/// `reverse_orientation` and the normals) and baked with `--write-gltf`: every corner's
/// `NORMAL` points out of the counter-clockwise front, which faces the camera (+z in the
/// description: the RIB reader mirrors z).
#[test]
fn the_baked_gltf_of_an_inside_out_quad_has_normals_out_of_its_front() {
    let dir = scratch_dir("rib-reversed-normals-gltf");
    std::fs::write(dir.join("s.rib"), scene(OUTSIDE_N)).unwrap();
    ok(&dir, &["convert", "s.rib", "-o", "s.ron"]);
    let ron = std::fs::read_to_string(dir.join("s.ron")).unwrap();
    assert!(ron.contains("reverse_orientation: true"), "{ron}");
    let bake = "bake: (resolution: (8, 8), uvs: Unwrap, outputs: [(kind: AmbientOcclusion(samples: 4), format: Png8)]),";
    std::fs::write(dir.join("s.ron"), ron.replacen("bake: None,", bake, 1)).unwrap();
    ok(&dir, &["bake", "s.ron", "-o", "out", "--write-gltf"]);
    let triangles = triangles_with_normals(&dir.join("out/s.glb"));
    assert_eq!(triangles.len(), 2);
    for ([a, b, c], normals) in triangles {
        let front = (b - a).cross(c - a).normalize();
        assert!(front.abs_diff_eq(Vec3::Z, 1e-6), "{front}");
        for n in normals {
            assert!(
                n.abs_diff_eq(front, 1e-6),
                "NORMAL {n} against the front {front}"
            );
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

//! Issue 18, families 3, 4 and 9: bounded recursion (RON nesting, phenomenon chains),
//! bounded phenomenon expansion, deep group chains flattened in linear memory, bounded
//! thread counts and file sizes, and a UTF-8 byte order mark accepted (RON, RIB and its
//! archives, `.mi`).

use crate::common::{quad_object, run_in, scratch_dir, small_scene, stderr_of};

#[test]
fn threads_above_the_limit_are_refused() {
    let dir = scratch_dir("threads-limit");
    let o = run_in(&dir, &["render", "scene.ron", "--threads", "100000"]);
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: invalid value '100000' for '--threads <THREADS>': 100000 is not in 1..=1024\n\nFor more information, try '--help'.\n"
    );
}

#[test]
fn deeply_nested_shader_nodes_state_the_limit() {
    let dir = scratch_dir("ron-nesting");
    let mut node = "(0.5, 0.5, 0.5)".to_string();
    for _ in 0..80 {
        node = format!("Mul({node}, (1, 1, 1))");
    }
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "").replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        &format!(r#"shader: Lambert(albedo: (1, 1, 1)), bind: {{"albedo": {node}}}"#),
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    let stderr = stderr_of(&o);
    assert!(
        stderr.starts_with("scene.ron:2:"),
        "located in the file: {stderr}"
    );
    assert!(
        stderr.contains(": error: values nested deeper than 128 levels\n  help: a scene file nests at most that deep: declare inner shader nodes as phenomena and call them with Graph(…)\n"),
        "{stderr}"
    );
    assert!(!stderr.contains("recursion_limit"), "{stderr}");
}

#[test]
fn a_chain_of_phenomena_beyond_the_limit_is_refused_where_it_starts() {
    let dir = scratch_dir("phenomenon-chain");
    let n = 3000;
    let mut phenomena = Vec::new();
    for i in 0..n {
        let body = if i + 1 < n {
            format!(r#"Graph("p{}", {{}})"#, i + 1)
        } else {
            "(0.5, 0.5, 0.5)".to_string()
        };
        phenomena.push(format!(r#"(name: "p{i}", output: {body})"#));
    }
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad")"#,
        "",
        &format!("    phenomena: [\n{}\n    ],\n", phenomena.join(",\n")),
    )
    .replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        r#"shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Graph("p0", {})}"#,
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:13:22: error: phenomenon \"p0\" starts a chain of 3000 nested phenomenon calls (p0 → p1 → … → p2999); the limit is 64\n  help: call fewer phenomena inside each other: inline some of them\n1 error in scene.ron\n"
    );
}

#[test]
fn phenomena_calling_each_other_twice_stop_at_the_expanded_size_limit() {
    // p(k) = Mul(p(k-1), p(k-1)) has 2^(k+1) - 1 nodes: p16 is the first past 100,000.
    let dir = scratch_dir("phenomenon-doubling");
    let mut phenomena = vec![r#"(name: "p0", output: (0.5, 0.5, 0.5))"#.to_string()];
    for k in 1..18 {
        phenomena.push(format!(
            r#"(name: "p{k}", output: Mul(Graph("p{j}", {{}}), Graph("p{j}", {{}})))"#,
            j = k - 1
        ));
    }
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad")"#,
        "",
        &format!("    phenomena: [\n{}\n    ],\n", phenomena.join(",\n")),
    )
    .replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        r#"shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Graph("p17", {})}"#,
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:29:45: error: phenomenon \"p15\" called here makes the expanded graph larger than 100000 nodes, the limit for one graph\n  help: every call is expanded in full: call a phenomenon once and pass its result in as a parameter to reuse it (Param(\"x\") used twice costs nothing), or nest fewer calls\n1 error in scene.ron\n"
    );
}

/// A chain of 10,000 groups, each placing the next: flattening kept the whole path string
/// on every level (about 300 MB here, 5.7 GB for 40,000 levels); now memory stays linear in
/// the depth, and `check` passes under a 256 MiB address-space limit.
#[test]
fn a_deep_chain_of_groups_is_flattened_in_linear_memory() {
    let dir = scratch_dir("deep-group-chain");
    let n = 10_000;
    let root = r#"(name: "q", of: "g0")"#;
    let mut instances = vec![root.to_string()];
    let mut groups = Vec::new();
    for k in 0..n {
        let of = if k + 1 < n {
            format!("g{}", k + 1)
        } else {
            "quad".to_string()
        };
        instances.push(format!(r#"(name: "i{k}", of: "{of}")"#));
        groups.push(format!(r#"(name: "g{k}", members: ["i{k}"])"#));
    }
    let scene = small_scene(&quad_object("quad"), root, "", "")
        .replace(
            &format!("instances: [{root}]"),
            &format!("instances: [{}]", instances.join(", ")),
        )
        .replace(
            r#"members: ["q"])]"#,
            &format!(r#"members: ["q"]), {}]"#, groups.join(", ")),
        );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let bin = env!("CARGO_BIN_EXE_stagelight");
    let o = std::process::Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 262144 && exec \"{bin}\" check scene.ron"
        ))
        .current_dir(&dir)
        .output()
        .expect("run stagelight");
    assert!(o.status.success(), "{}", stderr_of(&o));
}

#[test]
fn many_materials_calling_a_large_phenomenon_stop_at_the_scene_limit() {
    // p15 expands to 65,535 nodes, within one graph's limit; 16 materials calling it pass
    // the scene's 1,000,000 (with the phenomena's own checks, 131,054 nodes) at m13, and only
    // the call that crosses it is reported.
    let dir = scratch_dir("phenomenon-scene-limit");
    let mut phenomena = vec![r#"(name: "p0", output: (0.5, 0.5, 0.5))"#.to_string()];
    for k in 1..16 {
        phenomena.push(format!(
            r#"(name: "p{k}", output: Mul(Graph("p{j}", {{}}), Graph("p{j}", {{}})))"#,
            j = k - 1
        ));
    }
    let materials: Vec<String> = (0..16)
        .map(|k| format!(r#"(name: "m{k}", shader: Lambert(albedo: (1, 1, 1)), bind: {{"albedo": Graph("p15", {{}})}})"#))
        .collect();
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad")"#,
        "",
        &format!("    phenomena: [\n{}\n    ],\n", phenomena.join(",\n")),
    )
    .replace(
        r#"materials: [(name: "grey", shader: Lambert(albedo: (0.5, 0.5, 0.5)))]"#,
        &format!(
            "materials: [(name: \"grey\", shader: Lambert(albedo: (1, 1, 1))),\n{}]",
            materials.join(",\n")
        ),
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:16:68: error: phenomenon \"p15\" called here makes the scene's expanded graphs larger than 1000000 nodes together, the limit for one scene\n  help: every call is expanded in full: call a phenomenon once and pass its result in as a parameter to reuse it (Param(\"x\") used twice costs nothing), or nest fewer calls\n1 error in scene.ron\n"
    );
}

#[test]
fn an_endless_include_stops_at_the_size_limit() {
    let dir = scratch_dir("include-dev-zero");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.ron")).unwrap();
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "").replacen(
        "Scene(\n",
        "Scene(\n    include: [\"zero.ron\"],\n",
        1,
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:2:15: error: cannot read include file \"zero.ron\": larger than 64 MiB, the limit for a scene file\n1 error in scene.ron\n"
    );
}

#[test]
fn a_byte_order_mark_before_the_scene_is_accepted() {
    let dir = scratch_dir("bom");
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("scene.ron"), format!("\u{feff}{scene}")).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert!(o.status.success(), "{}", stderr_of(&o));
}

#[test]
fn a_byte_order_mark_before_a_rib_an_archive_or_a_mi_file_is_accepted() {
    let dir = scratch_dir("bom-rib-mi");
    let bom = "\u{feff}";
    let rib = "Display \"d.png\" \"file\" \"rgb\"\nFormat 16 16 1\nTranslate 0 0 3\nWorldBegin\nLightSource \"pointlight\" 1 \"intensity\" [10] \"from\" [0 0 -3]\nReadArchive \"ball.rib\"\nWorldEnd\n";
    std::fs::write(dir.join("bom.rib"), format!("{bom}{rib}")).unwrap();
    std::fs::write(
        dir.join("ball.rib"),
        format!("{bom}Sphere 0.5 -0.5 0.5 360\n"),
    )
    .unwrap();
    let plane = concat!(env!("CARGO_MANIFEST_DIR"), "/assets/seeds/mi/plane.mi");
    let mi = std::fs::read_to_string(plane).unwrap();
    std::fs::write(dir.join("bom.mi"), format!("{bom}{mi}")).unwrap();
    for scene in ["bom.rib", "bom.mi"] {
        let o = run_in(&dir, &["check", scene]);
        assert!(o.status.success(), "{scene}: {}", stderr_of(&o));
    }
}

#[test]
fn a_filter_wider_than_the_limit_is_refused() {
    let dir = scratch_dir("filter-radius");
    let scene = small_scene(
        &quad_object("quad"),
        r#"(name: "q", of: "quad")"#,
        "",
        "    options: (filter: Gaussian(radius: 1000000)),\n",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    let stderr = stderr_of(&o);
    assert!(stderr.starts_with("scene.ron:12:"), "{stderr}");
    assert!(
        stderr.contains(": error: radius must be at most 64 pixels, found 1000000\n"),
        "{stderr}"
    );
}

#[test]
fn objects_without_geometry_get_a_located_warning() {
    let dir = scratch_dir("empty-meshes");
    std::fs::write(dir.join("empty.obj"), "").unwrap();
    let scene = small_scene(
        r#"(name: "nothing", mesh: Obj(file: "empty.obj")),
        (name: "cage", mesh: Subdiv(vertices: [(0, 0, 0)], polygons: [])),"#,
        r#"(name: "n", of: "nothing"), (name: "c", of: "cage")"#,
        "",
        "",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    let stderr = stderr_of(&o);
    assert!(
        stderr.contains("scene.ron:5:9: warning: object \"nothing\": its mesh has no triangles; it renders nothing\n  help: check the mesh, or leave the object out\n"),
        "{stderr}"
    );
    assert!(
        stderr.contains("scene.ron:6:9: warning: object \"cage\": its subdivision mesh has no faces; it renders nothing\n"),
        "{stderr}"
    );
    assert!(
        !stderr.contains('\u{1b}'),
        "no colour codes into a pipe: {stderr:?}"
    );
}

/// A bake of an instance whose triangles were all dropped as degenerate (its four corners at
/// one point) says the instance has no triangles, alone and beside an instance that has
/// some; it said "its UVs cover no area" with the help to generate UVs, which cannot help.
#[test]
fn a_bake_of_an_instance_with_only_degenerate_triangles_says_it_has_no_triangles() {
    let flat = r#"(name: "flat", mesh: Inline(vertices: [(1, 1, 1), (1, 1, 1), (1, 1, 1), (1, 1, 1)], uvs: [(0, 0), (1, 0), (1, 1), (0, 1)], polygons: [[0, 1, 2, 3]]), material: "grey"),"#;
    let bake = r#"(name: "f", of: "flat", bake: (resolution: (4, 4), uvs: Mesh, outputs: [(kind: AmbientOcclusion(samples: 1))]))"#;
    let quad = crate::common::quad_object("quad");
    for (test, objects, instances, line) in [
        (
            "bake-degenerate-alone",
            flat.to_string(),
            bake.to_string(),
            7,
        ),
        (
            "bake-degenerate-beside",
            format!("{flat}\n        {quad}"),
            format!(r#"{bake}, (name: "q", of: "quad")"#),
            8,
        ),
    ] {
        let dir = scratch_dir(test);
        let scene = small_scene(&objects, &instances, "", "");
        std::fs::write(dir.join("scene.ron"), scene).unwrap();
        let o = run_in(&dir, &["bake", "scene.ron"]);
        assert_eq!(o.status.code(), Some(1), "{test}");
        let stderr = stderr_of(&o);
        assert!(
            stderr.ends_with(&format!(
                "scene.ron:{line}:17: error: bake request on instance \"f\": the instance has no triangles\n"
            )),
            "{test}: {stderr}"
        );
        assert_eq!(stderr.matches("error:").count(), 1, "{test}: {stderr}");
        assert_eq!(crate::common::dir_names(&dir), ["scene.ron"], "{test}");
    }
}

/// Bake UVs that cannot take a texel are refused, naming why, with nothing written: UVs at
/// one point (no area), and UVs wholly outside the unit square (the bake wrote an all-zero
/// texture with exit 0).
#[test]
fn bake_uvs_that_cover_no_texel_are_refused() {
    let cases = [
        (
            "bake-point-uvs",
            "(0.5, 0.5), (0.5, 0.5), (0.5, 0.5), (0.5, 0.5)",
            "texels_per_unit: 8",
            "its UVs cover no area (every triangle's UVs lie at one point or on a line)\n  help: give the mesh real UVs, or set `uvs: Unwrap` to generate lightmap UVs",
        ),
        (
            "bake-outside-uvs",
            "(2, 2), (3, 2), (3, 3), (2, 3)",
            "resolution: (8, 8)",
            "its UVs cover no texel of the texture (they lie outside [0, 1]², or between the sample positions)\n  help: bake UVs must lie in the unit square: set `uvs: Unwrap` to generate lightmap UVs",
        ),
    ];
    for (test, uvs, size, message) in cases {
        let dir = scratch_dir(test);
        let scene = small_scene(
            &format!(
                r#"(name: "quad", mesh: Inline(vertices: [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], uvs: [{uvs}], polygons: [[0, 1, 2, 3]]), material: "grey"),"#
            ),
            &format!(
                r#"(name: "q", of: "quad", bake: ({size}, uvs: Mesh, outputs: [(kind: AmbientOcclusion(samples: 1))]))"#
            ),
            "",
            "",
        );
        std::fs::write(dir.join("scene.ron"), scene).unwrap();
        let o = run_in(&dir, &["bake", "scene.ron"]);
        assert_eq!(o.status.code(), Some(1), "{test}");
        assert_eq!(
            stderr_of(&o),
            format!("scene.ron:7:17: error: bake request on instance \"q\": {message}\n"),
            "{test}"
        );
        assert_eq!(crate::common::dir_names(&dir), ["scene.ron"], "{test}");
    }
}

/// A bake density past f32's range is one error: it also said `texels_per_unit must be
/// positive, found 1000000000000000000000000000000000000000`, which is false.
#[test]
fn a_bake_density_past_f32_is_one_error() {
    let dir = scratch_dir("bake-density-1e39");
    let scene = small_scene(
        r#"(name: "quad", mesh: Grid(size_x: 1, size_y: 1), material: "grey"),"#,
        r#"(name: "q", of: "quad", bake: (texels_per_unit: 1e39, outputs: [(kind: AmbientOcclusion(samples: 1))]))"#,
        "",
        "",
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:7:65: error: texels_per_unit 1e39 is beyond the f32 range\n1 error in scene.ron\n"
    );
}

/// RIB `ReadArchive` and `.mi` `$include` files stop at the scene-file size limit too.
#[test]
fn an_endless_archive_or_mi_include_stops_at_the_size_limit() {
    let dir = scratch_dir("archive-dev-zero");
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.rib")).unwrap();
    std::os::unix::fs::symlink("/dev/zero", dir.join("zero.mi")).unwrap();
    std::fs::write(
        dir.join("scene.rib"),
        "Format 8 8 1\nWorldBegin\nReadArchive \"zero.rib\"\nWorldEnd\n",
    )
    .unwrap();
    std::fs::write(dir.join("scene.mi"), "$include \"zero.mi\"\n").unwrap();
    let o = run_in(&dir, &["check", "scene.rib"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr_of(&o).starts_with("scene.rib:3:13: error: cannot read archive \"zero.rib\": larger than 64 MiB, the limit for a scene file\n"),
        "{}",
        stderr_of(&o)
    );
    let o = run_in(&dir, &["check", "scene.mi"]);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr_of(&o).contains("scene.mi:1:10: error: cannot read include \"zero.mi\": larger than 64 MiB, the limit for a scene file\n"),
        "{}",
        stderr_of(&o)
    );
}

/// A 15 KB EXR whose header claims 60000 × 60000 RGBA pixels (a consistent chunk table, PIZ
/// blocks of 32 rows): read as a texture, the `exr` crate allocated its 72 GB up front and the
/// process aborted. Now its headers are read first and the file is refused, as a texture, as
/// a sweep reference and as a farm part file.
#[test]
fn an_exr_claiming_a_huge_image_is_refused_before_it_is_read() {
    let dir = scratch_dir("huge-exr");
    let fixture = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/images/claims_60000x60000.exr"
    );
    std::fs::copy(fixture, dir.join("huge.exr")).unwrap();
    let scene = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "").replace(
        r#"shader: Lambert(albedo: (0.5, 0.5, 0.5))"#,
        r#"shader: Lambert(albedo: (1, 1, 1)), bind: {"albedo": Image(file: "huge.exr")}"#,
    );
    std::fs::write(dir.join("scene.ron"), scene).unwrap();
    let claims = "a layer of 60000×60000 pixels in 4 channels: the file claims more than the";
    let o = run_in(&dir, &["check", "scene.ron"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    let stderr = stderr_of(&o);
    assert!(
        stderr.contains(&format!(
            ": error: cannot read image file \"huge.exr\": {claims} 268435456 samples (pixels × channels) this input may hold\n"
        )),
        "{stderr}"
    );
    let plain = small_scene(&quad_object("quad"), r#"(name: "q", of: "quad")"#, "", "");
    std::fs::write(dir.join("plain.ron"), plain).unwrap();
    let sweep = [
        "sweep",
        "plain.ron",
        "--knob",
        "spp=1",
        "--reference",
        "huge.exr",
    ];
    let o = run_in(&dir, &[&sweep[..], &["--out", "sweep"]].concat());
    assert_eq!(o.status.code(), Some(2), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!(
            "error: --reference huge.exr cannot be read as an RGB image ({claims} 268435456 samples (pixels × channels) this input may hold)\n  help: give a linear EXR image of the runs' size (without --reference, the sweep renders one and caches it in --out)\n"
        )
    );
    // Nothing written: not even the output directory (made once the reference is read).
    assert!(!dir.join("sweep").exists());
    let o = run_in(&dir, &["merge", "huge.exr", "-o", "merged.exr"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        format!("error: huge.exr: {claims} 4294967296 samples (pixels × channels) this input may hold\nnothing written\n")
    );
    assert!(!dir.join("merged.exr").exists());
}

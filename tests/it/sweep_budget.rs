//! `stagelight sweep` refuses what it cannot run honestly, before running anything: a knob
//! value (or the rendered reference) past the memory budget, a repeated value; and its
//! summary draws no conclusion its rows cannot carry. The budget cases run under
//! `ulimit -v` (4 GiB): had a refused setting been allocated, the process would abort.

use crate::common::{run_in, run_limited, scratch_dir, small_scene, stderr_of};

/// A sphere diced 8×8 per patch, which the `tessellation` knob refines.
fn sphere_scene(approximation: &str, extra: &str) -> String {
    small_scene(
        &format!(
            r#"(name: "ball", mesh: Sphere(radius: 1), material: "grey", approximation: {approximation}),"#
        ),
        r#"(name: "b", of: "ball")"#,
        "",
        extra,
    )
}

#[test]
fn a_knob_value_past_the_budget_refuses_the_whole_sweep_before_any_run() {
    let dir = scratch_dir("sweep-budget-tess");
    std::fs::write(
        dir.join("scene.ron"),
        sphere_scene("Parametric(u: 8, v: 8)", ""),
    )
    .unwrap();
    let o = run_limited(
        &dir,
        &[
            "sweep",
            "scene.ron",
            "--knob",
            "tessellation=1,0.001",
            "--reference-spp",
            "4",
            "--memory-limit",
            "1G",
            "--out",
            "o",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:5:82: error: with --knob tessellation=0.001, object \"ball\": 268435456 triangles of 8 patch(es) diced 4096×4096 need about 96.0 GiB, more than the memory budget of 1.0 GiB (--memory-limit)\n  help: leave tessellation=0.001 out of the sweep; or use fewer or coarser triangles, or raise the budget with --memory-limit BYTES\n1 error in scene.ron; nothing swept\n"
    );
    assert!(!dir.join("o").exists(), "nothing is written");
}

#[test]
fn a_photon_count_past_the_budget_is_refused_at_the_option() {
    let dir = scratch_dir("sweep-budget-photons");
    std::fs::write(
        dir.join("scene.ron"),
        sphere_scene(
            "Parametric(u: 8, v: 8)",
            "    options: (caustics: (photons: 1000)),\n",
        ),
    )
    .unwrap();
    let o = run_limited(
        &dir,
        &[
            "sweep",
            "scene.ron",
            "--knob",
            "photons=1000,4000000000",
            "--reference-spp",
            "4",
            "--memory-limit",
            "1G",
            "--out",
            "o",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:12:25: error: with --knob photons=4000000000, options.caustics: the 4000000000 photons of the photon map need about 953.7 GiB, more than the memory budget of 1.0 GiB (--memory-limit)\n  help: leave photons=4000000000 out of the sweep; or emit fewer photons, or raise the budget with --memory-limit BYTES\n1 error in scene.ron; nothing swept\n"
    );
    assert!(!dir.join("o").exists());
}

/// The reference runs at the scene's own setting: past the budget it is refused as `render`
/// refuses it, even when every knob value fits.
#[test]
fn a_reference_past_the_budget_is_refused_as_render_refuses_it() {
    let dir = scratch_dir("sweep-budget-reference");
    std::fs::write(
        dir.join("scene.ron"),
        sphere_scene("Parametric(u: 8000, v: 8000)", ""),
    )
    .unwrap();
    let o = run_limited(
        &dir,
        &[
            "sweep",
            "scene.ron",
            "--knob",
            "tessellation=1000",
            "--memory-limit",
            "1G",
            "--out",
            "o",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "scene.ron:5:82: error: object \"ball\": 268435456 triangles of 8 patch(es) diced 4096×4096 need about 96.0 GiB, more than the memory budget of 1.0 GiB (--memory-limit)\n  help: use fewer or coarser triangles, or raise the budget with --memory-limit BYTES\n1 error in scene.ron; nothing swept\n"
    );
    assert!(!dir.join("o").exists());
}

/// Adaptive rates are known only once diced: the sweep's runs carry the budget, so the
/// tessellator refuses them (located) instead of the allocation aborting the process.
#[test]
fn adaptive_rates_past_the_budget_fail_at_tessellate_in_a_sweep() {
    let dir = scratch_dir("sweep-budget-adaptive");
    std::fs::write(
        dir.join("scene.ron"),
        sphere_scene("Curvature(distance: 1e-9, angle: 0, max_subdiv: 12)", ""),
    )
    .unwrap();
    let o = run_limited(
        &dir,
        &[
            "sweep",
            "scene.ron",
            "--knob",
            "tessellation=1,0.5",
            "--reference-spp",
            "4",
            "--memory-limit",
            "1G",
            "--out",
            "o",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr_of(&o));
    assert_eq!(
        stderr_of(&o),
        "sweep: reference: 4 samples, tessellation=0.5, max_depth=4 (the scene's, as in the swept runs)\nscene.ron:5:82: error: object \"ball\": its approximation would make 268435456 triangles, about 96.0 GiB, more than the 2796202 the memory budget of 1.0 GiB (--memory-limit) allows one object\n  help: coarsen the approximation (a larger `edge` or `distance`, a smaller `max_subdiv`), or raise the budget with --memory-limit BYTES\n"
    );
    assert!(!dir.join("o").exists());
}

#[test]
fn a_repeated_knob_value_is_a_usage_error() {
    let dir = scratch_dir("sweep-repeated");
    std::fs::write(
        dir.join("scene.ron"),
        sphere_scene("Parametric(u: 8, v: 8)", ""),
    )
    .unwrap();
    let o = run_in(
        &dir,
        &["sweep", "scene.ron", "--knob", "spp=1,4,1", "--out", "o"],
    );
    assert_eq!(o.status.code(), Some(2));
    assert_eq!(
        stderr_of(&o),
        "error: knob spp: the value 1 is given twice; give each value once (every value is one row of the table)\n"
    );
    assert!(!dir.join("o").exists());
}

/// Two values cannot carry a fit, and an error no row reached is not extrapolated: the
/// summary says so and gives the smallest measured error.
#[test]
fn two_values_give_no_fit_and_unreached_errors_are_not_extrapolated() {
    let dir = scratch_dir("sweep-no-fit");
    std::fs::write(
        dir.join("scene.ron"),
        sphere_scene("Parametric(u: 8, v: 8)", ""),
    )
    .unwrap();
    let o = run_in(
        &dir,
        &[
            "sweep",
            "scene.ron",
            "--knob",
            "spp=4,1",
            "--reference-spp",
            "16",
            "--integrator",
            "direct",
            "--out",
            "o",
        ],
    );
    assert!(o.status.success(), "{}", stderr_of(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    let last = stdout.lines().last().unwrap();
    assert!(
        last.starts_with(
            "whole image: no fit (2 values with a measured time and error; a fit needs 3 or more); bias plateau: "
        ),
        "{last}"
    );
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("o/sweep.json")).unwrap()).unwrap();
    assert_eq!(json["slope"], serde_json::Value::Null);
    let smallest = json["smallest_rel_mse"].as_f64().unwrap();
    assert!(
        smallest > 1e-3,
        "the test needs an unreached 1e-3: {smallest}"
    );
    assert_eq!(json["seconds_to_rel_mse_1e3"], serde_json::Value::Null);
    assert!(
        last.ends_with(&format!(
            "; 1e-3 not reached (the smallest measured relMSE is {smallest:.2e})"
        )),
        "{last}"
    );
}

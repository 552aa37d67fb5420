//! The integration tests, in one binary (one module per former `tests/*.rs` file) so the
//! crate is linked once, not once per file. Fixtures stay in `tests/fixtures/`.

mod common;

mod adaptive_sampling;
mod assets;
mod bad_values;
mod bad_values_camera;
mod bad_values_lights;
mod bake;
mod cli;
mod cli_bake;
mod cli_photons;
mod cli_plan;
mod environment;
mod fuzz_corpus;
mod geometry_scene;
mod geometry_stages;
mod geometry_surfaces;
mod hard_cases_bake;
mod hard_cases_bump;
mod hard_cases_far;
mod hard_cases_rays;
mod interrupt;
mod lens_shaders;
mod light_scenes;
mod lights;
mod mesh_files;
mod photons;
mod radiometry;
mod ray_counts;
mod ray_layer;
mod ray_spawn;
mod rib;
mod rib_shading;
mod scene_errors;
mod scene_errors_lights;
mod scene_load;
mod shading_bsdf;
mod shading_fresnel;
mod shading_integrators;
mod shading_scenes;
mod skipped_stages;
mod stages;
mod sweep;
mod textures;
mod volume_shaders;

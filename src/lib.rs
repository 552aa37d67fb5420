//! stagelight: an offline renderer and texture baker in the lineage of mental ray.
//!
//! A scene (RON) loads into an ECS world (`hecs`) whose entities are cameras, lights,
//! materials, objects and instances. Rendering is an ordered table of stages
//! (`systems::STAGES`), each run only when the world holds something for it; the runner
//! ([`schedule`]) records what ran, why, how long it took and how much work it did.

pub mod accel;
pub mod accumulate;
pub mod adaptive;
pub mod bake;
pub mod budget;
pub mod camera_choice;
pub mod camera_space;
pub mod components;
pub mod contour;
pub mod cpu_time;
pub mod diagnostic;
pub mod diagnostic_needs;
pub mod diagnostic_view;
pub mod exact_sum;
pub mod exr_output;
pub mod farm;
pub mod features;
pub mod format_helps;
pub mod frame;
pub mod framebuffer;
pub mod geometry;
pub mod guard;
pub mod hash;
pub mod image_io;
pub mod image_reads;
pub mod limits;
pub mod log_format;
pub mod memory_budget;
pub mod noise;
pub mod part_refusals;
pub mod pattern;
pub mod photon;
mod prefetch;
pub mod procedural;
pub mod progress;
pub mod report;
pub mod sampling;
pub mod scene;
pub mod scene_view;
pub mod schedule;
pub mod settings;
pub mod shading;
pub mod stage_error;
pub mod sweep;
pub mod tasks;
pub mod tessellation;

#[path = "../systems/mod.rs"]
pub mod systems;

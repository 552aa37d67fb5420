//! Fuzz target: arbitrary bytes as a RIB file. The RIB lexer, request parser and builder
//! must return a description or located errors, never panic; a description converts to
//! RON that parses back.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.rib");
    match stagelight::scene::import::rib::read_rib(path, data) {
        Ok(scene) => {
            for w in &scene.warnings {
                assert!(w.problem.pos.line >= 1 && w.problem.pos.column >= 1);
            }
            if let Ok(text) = stagelight::scene::import::to_ron::to_ron(&scene.desc) {
                let _ = stagelight::scene::load_scene_str(&text, std::path::Path::new("fuzz.ron"));
            }
        }
        Err(errors) => {
            // Every problem found, the warnings with the errors: at least one error.
            assert!(errors.iter().any(|e| !e.problem.warning));
            for e in &errors {
                assert!(e.problem.pos.line >= 1 && e.problem.pos.column >= 1);
            }
        }
    }
});

//! Fuzz target: arbitrary bytes as a .mi file. The .mi lexer, statement and block readers and the assembly
//! must return a description or located errors, never panic; a description converts to
//! RON that parses back.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let path = std::path::Path::new("fuzz.mi");
    match stagelight::scene::import::mi::read_mi(path, data) {
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

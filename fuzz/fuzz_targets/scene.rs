//! Any bytes as a scene file: a typed error, or a scene whose report is all finite numbers.
#![no_main]
use libfuzzer_sys::fuzz_target;
use noncirc::report::{check_finite, EvaluationReport};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(scene) = noncirc::scene_file::parse_scene(text, "fuzz") else {
        return;
    };
    // Fine resolutions are valid but slow: they add nothing a fuzzer can find.
    if scene.resolution.samples_per_turn > 1440 {
        return;
    }
    if let Ok((report, _)) = EvaluationReport::from_scene(&scene) {
        check_finite(&report).expect("every number of a report is finite");
    }
});

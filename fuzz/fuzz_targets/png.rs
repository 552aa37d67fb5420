//! Fuzz target: arbitrary bytes as a PNG image (textures, displacement maps, glTF images).
//! Decoding returns an image whose sample count matches its dimensions and channels, with
//! every sample in [0, 1] as `rgba` and `luma` give it, or an error; never a panic, and no
//! allocation past the decoder's limit.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stagelight::image_io::png_codec::{decode_png, Samples};

fuzz_target!(|data: &[u8]| {
    if let Ok(img) = decode_png(data) {
        let len = match &img.samples {
            Samples::Eight(s) => s.len(),
            Samples::Sixteen(s) => s.len(),
        };
        assert_eq!(len, img.pixels() * img.channels);
        assert!((1..=4).contains(&img.channels));
        for p in 0..img.pixels().min(64) {
            assert!(img.rgba(p).iter().all(|v| (0.0..=1.0).contains(v)));
            assert!((0.0..=1.0).contains(&img.luma(p)));
        }
    }
});

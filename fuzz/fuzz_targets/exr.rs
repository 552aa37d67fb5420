//! Fuzz target: arbitrary bytes as an EXR image (textures; environment maps, sweep references
//! and farm part files pass the same size check first). Decoding gives width × height pixels
//! or an error; never a panic, and nothing allocated for a size the headers claim past the
//! check's limit.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stagelight::shading::texture::image::decode_exr;

fuzz_target!(|data: &[u8]| {
    if let Ok((width, height, texels, alpha)) = decode_exr(data) {
        assert_eq!(texels.len(), width as usize * height as usize);
        assert!(alpha.is_empty() || alpha.len() == texels.len());
    }
});

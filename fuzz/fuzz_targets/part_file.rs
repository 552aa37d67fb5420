//! Fuzz target: arbitrary bytes as a farm part file (`merge`'s input), read both as a render
//! part and as a bake part: a file that decodes encodes again and decodes to the same
//! header; anything else is an error, never a panic or a huge allocation.
#![no_main]

use libfuzzer_sys::fuzz_target;
use stagelight::farm::{bake_part_file, part_file};

fuzz_target!(|data: &[u8]| {
    if let Ok(part) = part_file::decode(data) {
        let again = part_file::encode(&part).expect("a decoded render part encodes");
        let back = part_file::decode(&again).expect("its encoding decodes");
        assert_eq!(back.header, part.header);
    }
    if let Ok(part) = bake_part_file::decode(data) {
        let again = bake_part_file::encode(&part).expect("a decoded bake part encodes");
        let back = bake_part_file::decode(&again).expect("its encoding decodes");
        assert_eq!(back.header, part.header);
    }
});

//! The `.npy` and depth-PNG readers on hostile bytes: valid files mutated (bytes flipped, cut
//! short, lengthened, headers' numbers replaced by extreme ones) never panic, abort or
//! allocate beyond reason; each answers with an array or an error. 100 000 inputs each here;
//! `YAROK_FUZZ_INPUTS=1000000` for a longer run.

use yarok_components::probe_images::{depth_from_png, png};
use yarok_components::tactile::npy::{self, NpyArray};
use yarok_core::component::ProbeImage;
use yarok_test::generator::{Generator, fuzz_inputs};

/// `valid` changed in one of several ways.
fn mutate(valid: &[u8], random: &mut Generator) -> Vec<u8> {
    let mut bytes = valid.to_vec();
    match random.below(6) {
        0 => {
            for _ in 0..=random.below(8) {
                let at = random.below(bytes.len());
                bytes[at] = random.next_u64() as u8;
            }
        }
        1 => bytes.truncate(random.below(bytes.len())),
        2 => bytes.extend((0..random.below(64)).map(|_| random.next_u64() as u8)),
        3 => {
            // A number in the header replaced by an extreme one.
            let extreme = [
                "18446744073709551615",
                "9223372036854775807",
                "-1",
                "0",
                "4294967296",
            ];
            if let Some(at) = bytes.iter().position(u8::is_ascii_digit) {
                let end = bytes[at..]
                    .iter()
                    .position(|b| !b.is_ascii_digit())
                    .map_or(bytes.len(), |e| at + e);
                let replacement = extreme[random.below(extreme.len())].as_bytes();
                bytes.splice(at..end, replacement.iter().copied());
            }
        }
        4 => {
            let at = random.below(bytes.len());
            bytes.splice(
                at..at,
                (0..random.below(16)).map(|_| random.next_u64() as u8),
            );
        }
        _ => {
            // Four bytes at a random place set to a 32-bit length-like value.
            if bytes.len() >= 4 {
                let at = random.below(bytes.len() - 3);
                let value = [0xFFFF_FFFFu32, 0x7FFF_FFFF, 0x0001_0000][random.below(3)];
                bytes[at..at + 4].copy_from_slice(&value.to_be_bytes());
            }
        }
    }
    bytes
}

#[test]
fn mutated_npy_files_are_read_or_refused_never_a_panic() {
    let valid = NpyArray {
        shape: vec![3, 4],
        data: (0..12).map(|i| i as f32 * 0.5).collect(),
    }
    .to_bytes();
    let mut random = Generator(0x9E37_79B9_7F4A_7C15);
    let (mut read, mut refused) = (0, 0);
    for _ in 0..fuzz_inputs() {
        match npy::parse(&mutate(&valid, &mut random)) {
            Ok(array) => {
                let count: usize = array.shape.iter().product();
                assert_eq!(count, array.data.len());
                read += 1;
            }
            Err(_) => refused += 1,
        }
    }
    assert!(read > 0 && refused > 0, "{read} read, {refused} refused");
}

#[test]
fn mutated_depth_pngs_are_read_or_refused_never_a_panic() {
    let valid = png(&ProbeImage::Depth {
        width: 6,
        height: 4,
        metres: (0..24).map(|i| 0.01 + i as f32 * 1e-4).collect(),
        unit: 1e-6,
    })
    .unwrap();
    let mut random = Generator(0x2545_F491_4F6C_DD1D);
    let (mut read, mut refused) = (0, 0);
    for _ in 0..fuzz_inputs() {
        match depth_from_png(&mutate(&valid, &mut random)) {
            Ok((width, height, metres)) => {
                assert_eq!(metres.len(), (width * height) as usize);
                read += 1;
            }
            Err(_) => refused += 1,
        }
    }
    assert!(read > 0 && refused > 0, "{read} read, {refused} refused");
}

//! Fixed-seed replay of the `gaussian_ggx` fuzz target's contract
//! (`fuzz/fuzz_targets/gaussian_ggx.rs`) without a fuzzer: the same decoder and checks
//! (`filtered_ndf::testing::fuzz::check_gaussian_ggx`) over seeded random byte strings and
//! every special-value tag in each kernel slot.

use filtered_ndf::testing::fuzz::check_gaussian_ggx;
use filtered_ndf::testing::rng::SplitMix64;

#[test]
fn seeded_random_bytes_gaussian_ggx() {
    let mut rng = SplitMix64(0xF022_0017);
    for _ in 0..1500 {
        let len = (rng.next_u64() % 160) as usize;
        let bytes: Vec<u8> = (0..len).map(|_| rng.next_u64() as u8).collect();
        check_gaussian_ggx(&bytes);
    }
}

#[test]
fn every_special_value_in_every_kernel_slot() {
    // Header, an isotropic roughness (head byte 0, then four ordinary floats: tag 13 is 1.0),
    // then the three kernel entries, one of them special (tags 0..=14), the others ordinary.
    for head in 0u8..4 {
        for slot in 0..3 {
            for tag in 0u8..15 {
                let mut bytes = vec![head, 0, 18, 60, 0, 13, 13, 13];
                for k in 0..3 {
                    if k == slot {
                        bytes.push(tag);
                    } else {
                        bytes.extend_from_slice(&[18, 100, 0]);
                    }
                }
                bytes.extend_from_slice(&[15, 0x40, 0xa0, 15, 0x20, 0x10, 13, 15, 0x80, 0x30]);
                check_gaussian_ggx(&bytes);
            }
        }
    }
}

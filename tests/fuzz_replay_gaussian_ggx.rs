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

/// The decoder's tag 15 for an ordinary value `v` in `[-2, 2]` (`u16 / 16383.75 - 2`).
fn ordinary(v: f64) -> [u8; 3] {
    let [a, b] = (((v + 2.0) * 16383.75).round() as u16).to_le_bytes();
    [15, a, b]
}

#[test]
fn every_special_value_in_every_kernel_slot() {
    // Header (bit 0 and 1: normalise `m` and `wo`), an isotropic roughness (head byte 0, then
    // four floats: `alpha` clamped from 1.6e-24, or 0.5), then the three kernel entries, one
    // of them special (tags 0..=14), the others ordinary (0.026, -2e-10, 0.026), then a
    // slope, `u`, and the directions `m` and `wo`: real directions above the horizon, so that
    // `d`, `lambda`, the visible sampler and its pdf see every special kernel.
    let alphas: [&[u8]; 2] = [&[18, 60, 0], &ordinary(0.5)];
    let others: [&[u8]; 3] = [&[18, 123, 0], &[18, 100, 1], &[18, 123, 0]];
    for head in 0u8..4 {
        for alpha in alphas {
            for slot in 0..3 {
                for tag in 0u8..15 {
                    let mut bytes = vec![head, 0];
                    bytes.extend_from_slice(alpha);
                    bytes.extend_from_slice(&[13, 13, 13]);
                    for (k, other) in others.iter().enumerate() {
                        if k == slot {
                            bytes.push(tag);
                        } else {
                            bytes.extend_from_slice(other);
                        }
                    }
                    for v in [0.504, -1.748, 0.7, 0.3, 0.3, -0.2, 0.9, -0.4, 0.5, 0.7] {
                        bytes.extend_from_slice(&ordinary(v));
                    }
                    check_gaussian_ggx(&bytes);
                }
            }
        }
    }
}

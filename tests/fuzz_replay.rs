//! Fixed-seed replay of the `ndf` fuzz target's contract (`fuzz/fuzz_targets/ndf.rs`) without
//! a fuzzer: the same decoder and checks (`filtered_ndf::testing::fuzz::check_ndf`) over
//! seeded random byte strings, every special value in every parameter slot, and the
//! regression inputs of every crash the fuzzer found.

use filtered_ndf::testing::fuzz::check_ndf;

struct Rng(u64);
impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
}

#[test]
fn seeded_random_bytes() {
    let mut rng = Rng(0xF022_0001);
    for _ in 0..4000 {
        let len = (rng.next() % 96) as usize;
        let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        check_ndf(&bytes);
    }
}

/// Every special-value tag (0..=14) in each of the first parameter and argument slots, for
/// every model/form/normalise header, with the other slots ordinary.
#[test]
fn every_special_value_in_every_slot() {
    // Tag 15 followed by two bytes is an ordinary value; 13 is 1.0.
    let ordinary = [15u8, 0x40, 0xa0];
    for head in 0u8..16 {
        for slot in 0..15 {
            for tag in 0u8..15 {
                let mut bytes = vec![head];
                for k in 0..15 {
                    if k == slot {
                        bytes.push(tag);
                    } else if k < 4 {
                        bytes.push(13); // roughness 1
                    } else {
                        bytes.extend_from_slice(&ordinary);
                    }
                }
                check_ndf(&bytes);
            }
        }
    }
}

/// Inputs that once broke the contract (found by the fuzzer or while writing the checks).
#[test]
fn regressions() {
    let cases: &[&[u8]] = &[
        // Empty input: everything decodes to NaN.
        &[],
        // Huge finite directions (f32::MAX components): Lambda once overflowed its quadratic
        // form; now rescaled.
        &[
            0, 13, 13, 13, 13, 13, 13, 11, 11, 11, 11, 11, 11, 11, 11, 11,
        ],
        &[1, 13, 13, 13, 13, 13, 13, 5, 5, 5, 5, 5, 5, 5, 5, 5],
    ];
    for c in cases {
        check_ndf(c);
    }
}

//! Fixed-seed replay of every fuzz target's contract (`fuzz/fuzz_targets/*.rs`) without a
//! fuzzer: the same decoders and checks (`filtered_ndf::testing::fuzz::check_*`) over seeded
//! random byte strings, every special value in every parameter slot (NDF family), and the
//! regression inputs of every crash the fuzzer found.

use filtered_ndf::testing::fuzz::{
    check_filter, check_isotropic, check_jacobian, check_ndf, check_rect, check_sampling,
    check_temporal,
};

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

/// `n` seeded random byte strings of length `0..max_len` through `check`.
fn replay(seed: u64, n: usize, max_len: u64, check: fn(&[u8])) {
    let mut rng = Rng(seed);
    for _ in 0..n {
        let len = (rng.next() % max_len) as usize;
        let bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        check(&bytes);
    }
}

#[test]
fn seeded_random_bytes() {
    replay(0xF022_0001, 4000, 96, check_ndf);
}

#[test]
fn seeded_random_bytes_filter() {
    replay(0xF022_0002, 3000, 256, check_filter);
}

#[test]
fn seeded_random_bytes_rect() {
    replay(0xF022_0003, 3000, 96, check_rect);
}

#[test]
fn seeded_random_bytes_isotropic() {
    replay(0xF022_0004, 3000, 128, check_isotropic);
}

#[test]
fn seeded_random_bytes_jacobian() {
    replay(0xF022_0005, 3000, 256, check_jacobian);
}

#[test]
fn seeded_random_bytes_sampling() {
    replay(0xF022_0006, 3000, 128, check_sampling);
}

#[test]
fn seeded_random_bytes_temporal() {
    replay(0xF022_0007, 3000, 256, check_temporal);
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

/// Every crash input the fuzzer found (`tests/data/fuzz_regressions/<target>/`, copied from
/// `fuzz/artifacts/<target>/`), replayed through its target's check.
#[test]
fn regression_corpus() {
    type Check = fn(&[u8]);
    let targets: [(&str, Check); 7] = [
        ("ndf", check_ndf),
        ("filter", check_filter),
        ("rect", check_rect),
        ("isotropic", check_isotropic),
        ("jacobian", check_jacobian),
        ("sampling", check_sampling),
        ("temporal", check_temporal),
    ];
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/fuzz_regressions");
    for (name, check) in targets {
        let Ok(dir) = std::fs::read_dir(root.join(name)) else {
            continue;
        };
        for entry in dir {
            let path = entry.unwrap().path();
            let bytes = std::fs::read(&path).unwrap();
            eprintln!("{}", path.display());
            check(&bytes);
        }
    }
}

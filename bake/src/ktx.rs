//! A KTX 2.0 writer for uncompressed 2-D textures with their whole mip chain: the container
//! the baker writes its chains in.
//!
//! # The file (KTX 2.0 specification, <https://registry.khronos.org/KTX/specs/2.0/ktxspec.v2.html>)
//! 1. The 12-byte identifier `«KTX 20»\r\n\x1A\n`.
//! 2. The header: `vkFormat`, `typeSize` (the byte size of one component, for endianness),
//!    `pixelWidth`, `pixelHeight`, `pixelDepth = 0` (2-D), `layerCount = 0` (not an array),
//!    `faceCount = 1`, `levelCount`, `supercompressionScheme = 0` (none).
//! 3. The index: where the data format descriptor (DFD) and the key/value data (KVD) lie;
//!    no supercompression global data.
//! 4. The level index, level 0 (the largest) first: each level's byte offset and length
//!    (`uncompressedByteLength` equal to the length: nothing is supercompressed).
//! 5. The DFD: one basic descriptor block (Khronos Data Format Specification 1.3, section
//!    5), colour model RGBSDA, primaries unspecified (the chains are data, not colour: three.js
//!    then loads them with `NoColorSpace`), transfer linear, straight alpha, one sample per
//!    channel with `sampleLower`/`sampleUpper` `0`/`255` for `UNORM` and the `f32` bit patterns
//!    of `-1`/`1` for `SFLOAT` (the values libktx's `createDFDUnpacked` writes).
//! 6. The KVD, sorted by key: `KTXorientation = "rd"` (rows top to bottom, as the baker stores
//!    them) and `KTXwriter`.
//! 7. The levels, smallest first, each starting at a multiple of `lcm(texel size, 4)` bytes,
//!    rows top to bottom, tightly packed (KTX 2 has no row padding).
//!
//! Level sizes follow the GPU rule `max(1, n >> k)`, the rule of
//! [`filtered_ndf::bake::ChainLayout`].

/// The texel formats the baker writes (Vulkan's `VkFormat` numbering).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `VK_FORMAT_R8_UNORM` (9): one 8-bit unsigned normalised channel.
    R8Unorm,
    /// `VK_FORMAT_R8G8B8A8_UNORM` (37).
    Rgba8Unorm,
    /// `VK_FORMAT_R16_SFLOAT` (76): one IEEE binary16 channel.
    R16Float,
    /// `VK_FORMAT_R16G16B16A16_SFLOAT` (97).
    Rgba16Float,
    /// `VK_FORMAT_R32_SFLOAT` (100).
    R32Float,
    /// `VK_FORMAT_R32G32B32A32_SFLOAT` (109).
    Rgba32Float,
}

impl Format {
    /// Its `VkFormat` number.
    pub const fn vk_format(self) -> u32 {
        match self {
            Format::R8Unorm => 9,
            Format::Rgba8Unorm => 37,
            Format::R16Float => 76,
            Format::Rgba16Float => 97,
            Format::R32Float => 100,
            Format::Rgba32Float => 109,
        }
    }

    /// Channels per texel.
    pub const fn channels(self) -> usize {
        match self {
            Format::R8Unorm | Format::R16Float | Format::R32Float => 1,
            Format::Rgba8Unorm | Format::Rgba16Float | Format::Rgba32Float => 4,
        }
    }

    /// Bytes per channel (KTX's `typeSize`).
    pub const fn type_size(self) -> usize {
        match self {
            Format::R8Unorm | Format::Rgba8Unorm => 1,
            Format::R16Float | Format::Rgba16Float => 2,
            Format::R32Float | Format::Rgba32Float => 4,
        }
    }

    /// Bytes per texel.
    pub const fn texel_bytes(self) -> usize {
        self.channels() * self.type_size()
    }

    const fn is_float(self) -> bool {
        !matches!(self, Format::R8Unorm | Format::Rgba8Unorm)
    }
}

/// The 12-byte file identifier.
pub const IDENTIFIER: [u8; 12] = [
    0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A,
];

/// `max(1, n >> k)`.
fn level_size(n: u32, k: usize) -> u32 {
    n.checked_shr(k as u32).unwrap_or(0).max(1)
}

/// The number of levels of a full chain, `1 + floor(log2(max(w, h)))`.
pub fn full_levels(width: u32, height: u32) -> usize {
    (u32::BITS - width.max(height).leading_zeros()) as usize
}

fn align(n: usize, a: usize) -> usize {
    n.div_ceil(a) * a
}

/// The data format descriptor of `format` (section 5 of the module docs), its total size
/// word included.
fn dfd(format: Format) -> Vec<u32> {
    let ch = format.channels();
    let block = 24 + 16 * ch as u32;
    // Colour model RGBSDA (1), primaries unspecified (0), transfer linear (1), straight alpha.
    let model = 1u32 | (1 << 16);
    let mut w = vec![
        4 + block,
        0,                           // vendor Khronos, descriptor type basic
        2 | (block << 16),           // version 2, block size
        model,                       // model, primaries, transfer, flags
        0,                           // texel block dimensions 1x1x1x1 (stored minus one)
        format.texel_bytes() as u32, // bytesPlane0
        0,
    ];
    let bits = 8 * format.type_size() as u32;
    for c in 0..ch {
        let id: u32 = [0, 1, 2, 15][c];
        let qualifiers: u32 = if format.is_float() { 0x80 | 0x40 } else { 0 };
        w.push((bits * c as u32) | ((bits - 1) << 16) | ((id | qualifiers) << 24));
        w.push(0);
        if format.is_float() {
            w.push((-1.0f32).to_bits());
            w.push(1.0f32.to_bits());
        } else {
            w.push(0);
            w.push((1u32 << bits) - 1);
        }
    }
    w
}

/// The key/value data: `KTXorientation` and `KTXwriter`, sorted by key, each entry padded to
/// four bytes.
fn kvd(writer: &str) -> Vec<u8> {
    let mut out = Vec::new();
    for (key, value) in [("KTXorientation", "rd"), ("KTXwriter", writer)] {
        let len = key.len() + 1 + value.len() + 1;
        out.extend_from_slice(&(len as u32).to_le_bytes());
        out.extend_from_slice(key.as_bytes());
        out.push(0);
        out.extend_from_slice(value.as_bytes());
        out.push(0);
        out.resize(align(out.len(), 4), 0);
    }
    out
}

/// The KTX 2.0 file of a `width x height` texture of `format` whose levels are `levels`
/// (level 0 first, each row-major with rows top to bottom, `texel_bytes` per texel, the
/// sizes of the GPU rule), `writer` its `KTXwriter` value. An error says which level has the
/// wrong length or why the chain is not a chain.
pub fn encode(
    format: Format,
    width: u32,
    height: u32,
    levels: &[&[u8]],
    writer: &str,
) -> Result<Vec<u8>, String> {
    if width == 0 || height == 0 {
        return Err("a KTX2 texture needs a non-zero size".into());
    }
    if levels.is_empty() || levels.len() > full_levels(width, height) {
        return Err(format!(
            "{} levels given; a {width}x{height} chain has 1 to {}",
            levels.len(),
            full_levels(width, height)
        ));
    }
    for (k, l) in levels.iter().enumerate() {
        let n = level_size(width, k) as usize * level_size(height, k) as usize;
        if l.len() != n * format.texel_bytes() {
            return Err(format!(
                "level {k} holds {} bytes, {} expected",
                l.len(),
                n * format.texel_bytes()
            ));
        }
    }
    let n = levels.len();
    let dfd = dfd(format);
    let kvd = kvd(writer);
    let index_end = 80 + 24 * n;
    let dfd_offset = index_end;
    let dfd_len = 4 * dfd.len();
    let kvd_offset = dfd_offset + dfd_len;
    let mut offset = kvd_offset + kvd.len();
    // lcm(texel size, 4): every texel size here is 1, 2, 4, 8 or 16 bytes.
    let level_align = format.texel_bytes().max(4);
    let mut placed = vec![(0usize, 0usize); n];
    for k in (0..n).rev() {
        offset = align(offset, level_align);
        placed[k] = (offset, levels[k].len());
        offset += levels[k].len();
    }
    let mut out = Vec::with_capacity(offset);
    out.extend_from_slice(&IDENTIFIER);
    for v in [
        format.vk_format(),
        format.type_size() as u32,
        width,
        height,
        0, // pixelDepth
        0, // layerCount
        1, // faceCount
        n as u32,
        0, // supercompressionScheme
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    for v in [
        dfd_offset as u32,
        dfd_len as u32,
        kvd_offset as u32,
        kvd.len() as u32,
    ] {
        out.extend_from_slice(&v.to_le_bytes());
    }
    out.extend_from_slice(&0u64.to_le_bytes()); // sgdByteOffset
    out.extend_from_slice(&0u64.to_le_bytes()); // sgdByteLength
    for &(o, l) in &placed {
        for v in [o as u64, l as u64, l as u64] {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    for w in &dfd {
        out.extend_from_slice(&w.to_le_bytes());
    }
    out.extend_from_slice(&kvd);
    for k in (0..n).rev() {
        out.resize(placed[k].0, 0);
        out.extend_from_slice(levels[k]);
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn u32_at(b: &[u8], at: usize) -> u32 {
        u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
    }

    #[test]
    fn the_header_and_levels_are_where_the_specification_puts_them() {
        // 5 x 3 RGBA16F: levels 5x3, 2x1, 1x1.
        let l0 = vec![1u8; 5 * 3 * 8];
        let l1 = vec![2u8; 2 * 8];
        let l2 = vec![3u8; 8];
        let f = encode(Format::Rgba16Float, 5, 3, &[&l0, &l1, &l2], "test").unwrap();
        assert_eq!(f[..12], IDENTIFIER);
        assert_eq!(u32_at(&f, 12), 97);
        assert_eq!(u32_at(&f, 16), 2);
        assert_eq!((u32_at(&f, 20), u32_at(&f, 24)), (5, 3));
        assert_eq!(u32_at(&f, 40), 3);
        // Level index at 80: offsets aligned to 8, smallest level first in the file.
        let off = |k: usize| u64::from_le_bytes(f[80 + 24 * k..88 + 24 * k].try_into().unwrap());
        assert!(off(2) < off(1) && off(1) < off(0));
        for k in 0..3 {
            assert_eq!(off(k) % 8, 0);
        }
        assert_eq!(f[off(0) as usize..], l0[..]);
        assert_eq!(f[off(2) as usize..off(2) as usize + 8], l2[..]);
        // The DFD's total size word and its four float samples.
        let dfd_at = u32_at(&f, 48) as usize;
        assert_eq!(u32_at(&f, dfd_at), 4 + 24 + 4 * 16);
        assert_eq!(u32_at(&f, dfd_at + 28 + 8), (-1.0f32).to_bits());
    }

    #[test]
    fn a_wrong_level_is_named() {
        let l0 = vec![0u8; 4 * 4];
        let l1 = vec![0u8; 3];
        let e = encode(Format::R8Unorm, 4, 4, &[&l0, &l1], "t").unwrap_err();
        assert!(e.contains("level 1"), "{e}");
        let e = encode(Format::R8Unorm, 4, 4, &[&l0, &l0, &l0, &l0], "t").unwrap_err();
        assert!(e.contains("1 to 3"), "{e}");
    }
}

//! stub

/// stub
pub fn check_temporal(_data: &[u8]) {}

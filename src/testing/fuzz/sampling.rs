//! stub

/// stub
pub fn check_sampling(_data: &[u8]) {}

//! stub

/// stub
pub fn check_isotropic(_data: &[u8]) {}

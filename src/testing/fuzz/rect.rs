//! stub

/// stub
pub fn check_rect(_data: &[u8]) {}

//! A Bevy plugin for filtered-ndf.

//! The built-in gallery scene, shipped inside the binary (`scenes/gallery.json`).

use super::{Scene, from_json_str};

/// The gallery's JSON text, as shipped.
pub const GALLERY_JSON: &str = include_str!("../../../../scenes/gallery.json");

/// The built-in gallery: one curve of each family and degree range splinescope shows,
/// including reconstructions of the papers' figures.
///
/// # Panics
/// Never for a released build: the embedded file is checked by the test suite.
#[must_use]
pub fn gallery() -> Scene {
    from_json_str(GALLERY_JSON).unwrap_or_else(|e| panic!("the built-in gallery is invalid: {e}"))
}

#[cfg(test)]
mod tests {
    #[test]
    fn gallery_reads() {
        let g = super::gallery();
        assert!(g.curves.len() >= 6);
    }
}

//! A point as scene and request files write it (a leaf of the written forms: the family
//! codecs and the scene document both use it).

use glam::DVec3;
use schemars::JsonSchema;
use serde::Serialize;

/// A point: `[x, y]` (`z = 0`) or `[x, y, z]`.
#[derive(Debug, Clone, Serialize, JsonSchema)]
#[serde(transparent)]
pub struct PointDoc(#[schemars(length(min = 2, max = 3))] pub Vec<f64>);

impl PointDoc {
    /// `[x, y]` when `z = 0`, else `[x, y, z]`.
    #[must_use]
    pub fn of(p: DVec3) -> PointDoc {
        if p.z == 0.0 {
            PointDoc(vec![p.x, p.y])
        } else {
            PointDoc(vec![p.x, p.y, p.z])
        }
    }

    /// Every point of `points`.
    #[must_use]
    pub fn all(points: &[DVec3]) -> Vec<PointDoc> {
        points.iter().copied().map(PointDoc::of).collect()
    }
}

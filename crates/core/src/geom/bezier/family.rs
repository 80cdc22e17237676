//! [`Bezier`]'s [`Family`] side: its points, structure edits and generated curves.

use glam::DVec3;

use crate::geom::family::Family;
use crate::geom::{Bezier, GeomError};

impl Family for Bezier {
    const NAME: &'static str = "bezier";

    fn with_point_on_polygon(&self, at: DVec3) -> Result<(Bezier, usize), GeomError> {
        let (points, leg, _) = crate::geom::structure::insert_on_polygon(self.points(), at);
        Ok((Bezier::try_new(points)?, leg + 1))
    }

    fn with_point_removed(&self, index: usize) -> Result<Bezier, GeomError> {
        Bezier::try_new(crate::geom::structure::without(
            self.points(),
            index,
            2,
            Self::NAME,
        )?)
    }

    fn generated(degree: usize, point: &mut dyn FnMut() -> DVec3) -> Result<Bezier, GeomError> {
        Bezier::try_new((0..=degree).map(|_| point()).collect())
    }

    fn control_points(&self) -> &[DVec3] {
        self.points()
    }

    fn with_control_points(&self, points: Vec<DVec3>) -> Result<Bezier, GeomError> {
        Bezier::try_new(points)
    }
}

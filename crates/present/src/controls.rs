//! The panel's controls as data: what a curve lets a person change, with labels and hints
//! ([`Control`]), and the values given back ([`ControlValue`]). The viewer draws them and
//! applies changes through [`crate::Present::apply_control`]; tests drive them the same way.

use glam::DVec3;
use splinescope_core::geom::GeomError;

/// Why a control cannot be set.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ControlError {
    /// A control the curve does not have, or a value of the wrong kind for it.
    #[error("{family} curves have no control {control}")]
    Unknown {
        /// The curve's family.
        family: &'static str,
        /// The control and the value given.
        control: String,
    },
    /// A value the family refuses (its message names it).
    #[error(transparent)]
    Geom(#[from] GeomError),
}

impl ControlError {
    /// The field a refused value belongs to (as [`GeomError::field`] names it), or empty
    /// for an unknown control.
    #[must_use]
    pub fn field(&self) -> String {
        match self {
            ControlError::Unknown { .. } => String::new(),
            ControlError::Geom(e) => e.field(),
        }
    }
}

/// The error for a control a family does not have (or a value of the wrong kind).
#[must_use]
pub fn unknown_control(family: &'static str, id: ControlId, value: ControlValue) -> ControlError {
    ControlError::Unknown {
        family,
        control: format!("{id} = {value:?}"),
    }
}

/// Names one control of a curve: a key and up to two indices (`a^i_j` is `("a", [i, j])`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct ControlId {
    /// What the control sets (`"t_star"`, `"v"`, `"a"`, `"elevate"`, …).
    pub key: &'static str,
    /// Indices, for controls that come in families (`[member, group]`); zeros otherwise.
    pub index: [usize; 2],
}

impl ControlId {
    /// A control without indices.
    #[must_use]
    pub const fn new(key: &'static str) -> ControlId {
        ControlId { key, index: [0, 0] }
    }
}

impl std::fmt::Display for ControlId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.index == [0, 0] {
            write!(f, "{}", self.key)
        } else {
            write!(f, "{}[{}, {}]", self.key, self.index[0], self.index[1])
        }
    }
}

/// A value given to a control.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ControlValue {
    /// For [`ControlKind::Number`].
    Number(f64),
    /// For [`ControlKind::Vector`].
    Vector(DVec3),
    /// For [`ControlKind::Toggle`].
    Toggle(bool),
    /// For [`ControlKind::Choice`]: the index of the option.
    Choice(usize),
    /// For [`ControlKind::Action`].
    Press,
}

/// What a control edits, and how.
#[derive(Debug, Clone, PartialEq)]
pub enum ControlKind {
    /// A number with a suggested range (typed values outside it are given to the family,
    /// which accepts or refuses them: never clamped).
    Number {
        /// The current value.
        value: f64,
        /// The slider's range.
        range: (f64, f64),
        /// The bands of values with a wanted property (a NUBMP parameter's
        /// variation-diminishing ranges), drawn on the slider; empty when there are none.
        bands: Vec<(f64, f64)>,
    },
    /// A vector.
    Vector {
        /// The current value.
        value: DVec3,
    },
    /// On or off.
    Toggle {
        /// The current value.
        value: bool,
    },
    /// One of several named options.
    Choice {
        /// The options' labels.
        options: Vec<&'static str>,
        /// The selected option's index.
        selected: usize,
    },
    /// A button.
    Action,
    /// Text only (what the structure is, a warning).
    Note {
        /// Whether the note warns (drawn in red).
        warning: bool,
    },
}

impl ControlKind {
    /// Whether a change through this control is one step on its own (a button, a toggle,
    /// a choice), rather than one of a stream of drags that undo merges.
    #[must_use]
    pub fn is_discrete(&self) -> bool {
        matches!(
            self,
            ControlKind::Toggle { .. } | ControlKind::Choice { .. } | ControlKind::Action
        )
    }
}

/// One of the panel's controls for a curve.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    /// Which control.
    pub id: ControlId,
    /// Its label (for a note, the text).
    pub label: String,
    /// A longer explanation shown on hover, or a range shown beside it.
    pub hint: Option<String>,
    /// What it edits.
    pub kind: ControlKind,
}

impl Control {
    /// The "elevate degree" button: the same curve with one more control point.
    #[must_use]
    pub fn elevate() -> Control {
        Control {
            id: ControlId::new("elevate"),
            label: "elevate degree".into(),
            hint: Some("the same curve with one more control point".into()),
            kind: ControlKind::Action,
        }
    }

    /// A text line.
    #[must_use]
    pub fn note(text: impl Into<String>, warning: bool) -> Control {
        Control {
            id: ControlId::new("note"),
            label: text.into(),
            hint: None,
            kind: ControlKind::Note { warning },
        }
    }
}

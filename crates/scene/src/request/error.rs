//! The request error and the JSON paths it names (apart from the requests' reading and
//! running, which both use it).

use thiserror::Error;

use crate::format::SceneError;
use crate::jsonread::Node;
use splinescope_core::solve::SolveError;

/// Why a request could not be applied: the path of the offending value in the request
/// document (`[1].target`, `first`) and what is wrong.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{}{message}", crate::format::at(path))]
pub struct RequestError {
    /// Where, as a JSON path in the request document; empty for the document as a whole.
    pub path: String,
    /// What.
    pub message: String,
}

impl From<SceneError> for RequestError {
    fn from(e: SceneError) -> RequestError {
        RequestError {
            path: e.path,
            message: e.kind.to_string(),
        }
    }
}

pub(super) fn at(node: &Node<'_>, field: &str, e: &SolveError) -> RequestError {
    let base = node.display_path();
    RequestError {
        path: if field.is_empty() {
            base
        } else if node.path.is_empty() {
            field.to_owned()
        } else {
            format!("{base}.{field}")
        },
        message: e.to_string(),
    }
}

/// `field` of the object at `node`, as a JSON path.
pub(crate) fn field_path(node: &Node<'_>, field: &str) -> String {
    if node.path.is_empty() {
        field.to_owned()
    } else {
        format!("{}.{field}", node.path)
    }
}

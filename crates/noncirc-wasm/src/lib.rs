//! noncirc in the browser: the design studio's WebAssembly module.
//!
//! A thin layer over the `noncirc` library, as the CLI and the Python package are: the
//! studio's numbers are the CLI's because they come from the same functions (scene files,
//! overrides, reports, the search executor). Results cross into JavaScript as JSON text;
//! errors as `Error` objects carrying the core's message.

mod design;
mod dynamics;
mod fit;
mod search;
mod view;

pub use design::Design;
pub use fit::{Fit, Repair};
pub use search::Search;

use wasm_bindgen::JsError;

/// Any error as a JavaScript `Error` with the library's message.
fn js_error(e: impl std::fmt::Display) -> JsError {
    JsError::new(&e.to_string())
}

/// A value as JSON text (every value sent is serialisable; a failure says what failed).
fn to_json(value: &impl serde::Serialize) -> Result<String, JsError> {
    serde_json::to_string(value).map_err(js_error)
}

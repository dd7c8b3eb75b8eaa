//! The page, built into the binary: no second server, nothing from the internet.

/// The page (`/` and any path but the assets').
pub const HTML: &str = include_str!("../page/index.html");
/// Its script (`/app.js`).
pub const SCRIPT: &str = include_str!("../page/app.js");
/// Its style (`/style.css`).
pub const STYLE: &str = include_str!("../page/style.css");

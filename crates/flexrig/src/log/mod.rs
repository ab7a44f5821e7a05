//! The MCAP logs and their Foxglove layouts: the log's own messages ([`messages`]), the recorder
//! that writes a run's frames, sensors and 3D scene ([`mcap`]), a run logged to a file written
//! whole or not at all ([`file`]), and the layout written beside each log ([`layout`]).
//!
//! May use: `shared`.

pub mod file;
pub mod layout;
pub mod mcap;
pub mod messages;

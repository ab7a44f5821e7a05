//! rig (work in progress)

//! botsim

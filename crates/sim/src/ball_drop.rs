//! Ball drop on an elastic half-space (being written).

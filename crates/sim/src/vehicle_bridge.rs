//! Vehicle over a bridge with contact, coupled every time step (being written).

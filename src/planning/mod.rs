//! Point-to-point moves: the fastest obstacle-free move of one robot between two poses.

//! The Work-Cell Problem: the graph of travel times, the sequencer and the feedback loop.

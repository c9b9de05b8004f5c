//! Placeholder: Pareto-front optimisers (being written).

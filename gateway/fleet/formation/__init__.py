"""Formation planning: slot geometry, travel-minimising slot assignment, and separation by altitude layers."""

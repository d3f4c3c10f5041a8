"""Qt view of the Array Editor."""

"""Array Editor: controller arrays and parameters as one editable list, with .zba templates (ide-spec 5)."""

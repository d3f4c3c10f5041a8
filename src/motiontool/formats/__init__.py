"""File formats without Qt, one module per docs/formats/ page: zbc (configuration files; its `[fc300]` section in
zbc_drive), dat (one CAM curve's array), zba (array definitions). The editors, the CLI and the UI read and write
files through them (issue 27 item 6)."""

"""Link requests off the GUI thread, shared by every Qt window of the tool (issue 27 item 2, decision I34): the
IDE's (`ui/`) and the oscilloscope's (`scope/ui/`), which the layers keep from importing each other. Qt by design,
like the `ui` packages; below the tools and `ui` in the layers.

`jobs`: `LinkJobs` (a view's requests, one after another), `PollJob` (one poll at a time), `wait_off_gui`;
`waiting`: a command waiting for its controller while its window paints, says so and drops what would start a
command again (`waiting(window, text, work)`)."""

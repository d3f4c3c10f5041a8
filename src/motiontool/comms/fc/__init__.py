"""The Danfoss FC protocol (RS-485 / USB): telegrams, the master link, the virtual drive's slave side."""

"""aposs"""

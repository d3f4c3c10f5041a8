"""scope/ui"""

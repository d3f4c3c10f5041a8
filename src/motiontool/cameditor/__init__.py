"""cameditor"""

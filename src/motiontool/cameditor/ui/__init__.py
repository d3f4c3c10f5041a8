"""cameditor/ui"""
